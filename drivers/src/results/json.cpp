#include "roadload/results/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "roadload/text_scan.hpp"

namespace roadload::results {

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const auto& [name, value] : members_) {
    if (name == key) return &value;
  }
  return nullptr;
}

std::optional<double> JsonValue::number_at(std::string_view path) const {
  const JsonValue* v = this;
  while (v != nullptr && !path.empty()) {
    const std::size_t dot = path.find('.');
    v = v->find(path.substr(0, dot));
    path = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  }
  if (v == nullptr || !v->is_number()) return std::nullopt;
  return v->number();
}

// Recursive descent, nesting bounded: a results file is a few levels deep, a hostile one is not.
class JsonParser {
 public:
  JsonParser(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  Parsed<JsonValue> document() {
    JsonValue root;
    if (!value(root, 0)) return *error_;
    skip_space();
    if (pos_ < text_.size()) {
      fail("", "unexpected text after the document");
      return *error_;
    }
    return root;
  }

 private:
  static constexpr int kMaxDepth = 32;

  bool fail(const std::string& field, const std::string& message) {
    error_ = ParseError{source_, line_, field, message};
    return false;
  }

  void skip_space() { pos_ = skip_whitespace(text_, pos_, line_); }

  bool literal(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  bool value(JsonValue& out, int depth) {
    skip_space();
    out.line_ = line_;
    if (depth > kMaxDepth) return fail("", "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    if (pos_ >= text_.size()) return fail("", "unexpected end of the document");
    const char c = text_[pos_];
    if (c == '{') return object(out, depth);
    if (c == '[') return array(out, depth);
    if (c == '"') {
      out.kind_ = JsonValue::Kind::string;
      return string(out.string_);
    }
    if (literal("true") || literal("false")) {
      out.kind_ = JsonValue::Kind::boolean;
      out.boolean_ = c == 't';
      return true;
    }
    if (literal("null")) return true;
    return number(out);
  }

  bool number(JsonValue& out) {
    const char* begin = text_.data() + pos_;
    const char* end = text_.data() + text_.size();
    double v = 0;
    const auto [ptr, ec] = std::from_chars(begin, end, v);
    if (ec != std::errc() || ptr == begin) {
      const std::size_t stop = text_.find_first_of(",}]\n", pos_);
      return fail("", "expected a value, got '" + std::string(text_.substr(pos_, stop - pos_)) + "'");
    }
    pos_ += static_cast<std::size_t>(ptr - begin);
    out.kind_ = JsonValue::Kind::number;
    out.number_ = v;
    return true;
  }

  bool string(std::string& out) {
    ++pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == '"') return true;
      if (c == '\n') break;
      if (c != '\\') {
        out.push_back(c);
        continue;
      }
      if (pos_ >= text_.size()) break;
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/': out.push_back(e); break;
        case 'b': out.push_back('\b'); break;
        case 'f': out.push_back('\f'); break;
        case 'n': out.push_back('\n'); break;
        case 'r': out.push_back('\r'); break;
        case 't': out.push_back('\t'); break;
        case 'u':
          if (!unicode(out)) return false;
          break;
        default: return fail("", std::string("unknown escape \\") + e + " in a string");
      }
    }
    return fail("", "unterminated string");
  }

  bool unicode(std::string& out) {
    unsigned code = 0;
    if (pos_ + 4 > text_.size() ||
        std::from_chars(text_.data() + pos_, text_.data() + pos_ + 4, code, 16).ptr != text_.data() + pos_ + 4) {
      return fail("", "\\u needs four hex digits");
    }
    pos_ += 4;
    // UTF-8; a surrogate half stays as its own (invalid) code point rather than failing the file.
    if (code < 0x80) {
      out.push_back(static_cast<char>(code));
    } else if (code < 0x800) {
      out.push_back(static_cast<char>(0xC0 | (code >> 6)));
      out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
    } else {
      out.push_back(static_cast<char>(0xE0 | (code >> 12)));
      out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
      out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
    }
    return true;
  }

  bool eat(char c) {
    if (pos_ >= text_.size() || text_[pos_] != c) return false;
    ++pos_;
    return true;
  }

  bool array(JsonValue& out, int depth) {
    out.kind_ = JsonValue::Kind::array;
    ++pos_;
    skip_space();
    if (eat(']')) return true;
    while (true) {
      out.items_.emplace_back();
      if (!value(out.items_.back(), depth + 1)) return false;
      skip_space();
      if (eat(']')) return true;
      if (!eat(',')) return fail("", "expected ',' or ']' in an array");
    }
  }

  bool object(JsonValue& out, int depth) {
    out.kind_ = JsonValue::Kind::object;
    ++pos_;
    skip_space();
    if (eat('}')) return true;
    while (true) {
      skip_space();
      std::string key;
      if (pos_ >= text_.size() || text_[pos_] != '"') return fail("", "expected a member name in quotes");
      if (!string(key)) return false;
      skip_space();
      if (!eat(':')) return fail(key, "expected ':' after the member name");
      out.members_.emplace_back(key, JsonValue{});
      if (!value(out.members_.back().second, depth + 1)) {
        if (error_->field.empty()) error_->field = key;
        return false;
      }
      skip_space();
      if (eat('}')) return true;
      if (!eat(',')) return fail(key, "expected ',' or '}' after the member");
    }
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  long line_ = 1;
  std::optional<ParseError> error_;
};

Parsed<JsonValue> parse_json(std::string_view text, const std::string& source) { return JsonParser(text, source).document(); }

Parsed<JsonValue> read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParseError{path, 0, "", "cannot be opened"};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return ParseError{path, 0, "", "could not be read"};
  return parse_json(text.str(), path);
}

std::string json_quote(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned>(c));
      out += esc;
    } else {
      out += c;
    }
  }
  out += '"';
  return out;
}

std::string json_number(double v, const char* format) {
  if (!std::isfinite(v)) return "null";
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

}  // namespace roadload::results
