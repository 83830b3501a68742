#pragma once
// Reading TOML configuration (routes, scenarios, vehicles) with errors that name file, line and field.
#include <toml++/toml.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/toml_text.hpp"

namespace roadload::detail {

// Thrown inside a parse, caught at its entry point and returned as a value.
struct TomlFailure {
  ParseError error;
};

class TomlFields {
 public:
  explicit TomlFields(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::node* n, std::string field, std::string message) const {
    const long line = n != nullptr ? static_cast<long>(n->source().begin.line) : 0;
    throw TomlFailure{ParseError{source_, line, std::move(field), std::move(message)}};
  }

  std::optional<double> number(const toml::table& t, std::string_view key, const std::string& where) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    auto v = n->value<double>();
    if (!v) fail(n, where + std::string(key), "expected a number");
    // TOML's nan and inf are no setting of anything physical.
    if (!std::isfinite(*v)) fail(n, where + std::string(key), "expected a finite number");
    return *v;
  }
  double number(const toml::table& t, std::string_view key, const std::string& where, double fallback) const {
    return number(t, key, where).value_or(fallback);
  }
  double required_number(const toml::table& t, std::string_view key, const std::string& where) const {
    if (auto v = number(t, key, where)) return *v;
    fail(&t, where + std::string(key), "required key missing");
  }
  // A number that must be finite and within [lo, hi]: a physical quantity.
  double required_in(const toml::table& t, std::string_view key, const std::string& where, double lo, double hi) const {
    const double v = required_number(t, key, where);
    if (!std::isfinite(v) || v < lo || v > hi) {
      fail(t.get(key), where + std::string(key), "outside " + format_range(lo, hi));
    }
    return v;
  }
  // An array of numbers, each finite and within [lo, hi].
  std::vector<double> required_numbers(const toml::table& t, std::string_view key, const std::string& where, double lo,
                                       double hi) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) fail(&t, where + std::string(key), "required key missing");
    const toml::array* a = n->as_array();
    if (a == nullptr) fail(n, where + std::string(key), "expected an array of numbers");
    std::vector<double> out;
    for (const toml::node& item : *a) {
      const auto v = item.value<double>();
      if (!v) fail(&item, where + std::string(key), "expected a number");
      if (!std::isfinite(*v) || *v < lo || *v > hi) fail(&item, where + std::string(key), "outside " + format_range(lo, hi));
      out.push_back(*v);
    }
    return out;
  }
  std::optional<std::string> text(const toml::table& t, std::string_view key, const std::string& where) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) fail(n, where + std::string(key), "expected a string");
    return std::string(*n->value<std::string_view>());
  }
  std::string required_text(const toml::table& t, std::string_view key, const std::string& where) const {
    if (auto v = text(t, key, where)) return *v;
    fail(&t, where + std::string(key), "required key missing");
  }
  std::optional<bool> flag(const toml::table& t, std::string_view key, const std::string& where) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_boolean()) fail(n, where + std::string(key), "expected true or false");
    return *n->value<bool>();
  }
  // A sub-table, or nothing when absent; anything else under that key is an error.
  const toml::table* table(const toml::table& t, std::string_view key) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(n, std::string(key), "expected a table [" + std::string(key) + "]");
    return n->as_table();
  }
  // A key the reader does not know is a typo until proven otherwise: stop at it.
  void only(const toml::table& t, std::initializer_list<std::string_view> known, const std::string& where) const {
    only(t, std::vector<std::string_view>(known), where);
  }
  void only(const toml::table& t, const std::vector<std::string_view>& known, const std::string& where) const {
    for (const auto& [key, node] : t) {
      if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
        fail(&node, where + std::string(key.str()), "unknown key");
      }
    }
  }
  const std::string& source() const { return source_; }

 private:
  static std::string format_range(double lo, double hi) {
    char text[64];
    std::snprintf(text, sizeof text, "%g..%g", lo, hi);
    return text;
  }
  std::string source_;
};

// Parses a TOML file; syntax errors come back with their line, UTF-8 outside strings and comments
// too (toml_text.hpp).
inline Parsed<toml::table> parse_toml_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return ParseError{path, 0, "file", "Is a directory"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParseError{path, 0, "file", std::string("cannot be opened: ") + std::strerror(errno)};
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (const auto line = non_ascii_outside_strings(text)) {
    return ParseError{path, *line, "syntax", "a character that is not ASCII outside a string or comment"};
  }
  toml::parse_result r = toml::parse(text, path);
  if (!r) {
    const auto& e = r.error();
    return ParseError{path, static_cast<long>(e.source().begin.line), "syntax", std::string(e.description())};
  }
  return std::move(r).table();
}

}  // namespace roadload::detail
