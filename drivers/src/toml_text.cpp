#include "roadload/toml_text.hpp"

#include <cstdio>

namespace roadload {

std::string toml_quoted(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if ((u < 0x20 && c != '\t') || u == 0x7F) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04X", static_cast<unsigned>(u));
      out += esc;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace roadload

namespace roadload::detail {

std::optional<long> non_ascii_outside_strings(std::string_view text) {
  enum class In { code, comment, basic, literal, basic_multi, literal_multi };
  In in = In::code;
  long line = 1;
  auto at = [&](std::size_t i, std::string_view s) { return text.substr(i, s.size()) == s; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (in == In::comment || in == In::basic || in == In::literal) in = In::code;  // single-line ones end here
      continue;
    }
    switch (in) {
      case In::code:
        if (static_cast<unsigned char>(c) > 0x7F) return line;
        if (c == '#') {
          in = In::comment;
        } else if (at(i, "\"\"\"")) {
          in = In::basic_multi;
          i += 2;
        } else if (at(i, "'''")) {
          in = In::literal_multi;
          i += 2;
        } else if (c == '"') {
          in = In::basic;
        } else if (c == '\'') {
          in = In::literal;
        }
        break;
      case In::comment: break;
      case In::basic:
        if (c == '\\') {
          if (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (c == '"') {
          in = In::code;
        }
        break;
      case In::literal:
        if (c == '\'') in = In::code;
        break;
      case In::basic_multi:
        if (c == '\\') {
          if (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (at(i, "\"\"\"")) {
          in = In::code;
          i += 2;
        }
        break;
      case In::literal_multi:
        if (at(i, "'''")) {
          in = In::code;
          i += 2;
        }
        break;
    }
  }
  return std::nullopt;
}

}  // namespace roadload::detail
