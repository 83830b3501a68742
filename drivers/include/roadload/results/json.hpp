#pragma once
// A JSON reader for the results files roadload writes (trip.json): values, arrays and objects,
// with the line of each value kept so that a reader can say where a field is missing or wrong;
// and the one string quoting every JSON writer uses.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"

namespace roadload::results {

class JsonValue {
 public:
  enum class Kind { null, boolean, number, string, array, object };

  Kind kind() const { return kind_; }
  long line() const { return line_; }
  bool is_number() const { return kind_ == Kind::number; }
  double number() const { return number_; }
  bool boolean() const { return boolean_; }
  const std::string& string() const { return string_; }
  const std::vector<JsonValue>& items() const { return items_; }
  // Members in the order they appear in the file.
  const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }
  // The member named `key` of an object; nullptr when absent or when this is not an object.
  const JsonValue* find(std::string_view key) const;
  // The number at `path` (keys separated by '.'), if every step exists and the last is a number.
  std::optional<double> number_at(std::string_view path) const;

 private:
  friend class JsonParser;
  Kind kind_ = Kind::null;
  long line_ = 0;
  bool boolean_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

// `source` names the text in errors (usually its path).
Parsed<JsonValue> parse_json(std::string_view text, const std::string& source);
Parsed<JsonValue> read_json_file(const std::string& path);

// A JSON string literal: quotes, backslashes and control characters escaped.
std::string json_quote(std::string_view s);
// A JSON number, printf's `format` of it (six significant digits by default, as a C++ stream
// writes a double); null when it is not finite, which JSON cannot hold.
std::string json_number(double v, const char* format = "%.6g");

}  // namespace roadload::results
