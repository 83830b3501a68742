#pragma once
// One error type for every parser: a user must be able to find the offending byte from the message.
#include <string>
#include <utility>
#include <variant>

namespace roadload {

struct ParseError {
  std::string file;   // path or logical source name
  long line = 0;      // 1-based; 0 when the error is not tied to a line
  std::string field;  // which field of the line, e.g. "timestamp", "SG_ factor"
  std::string message;

  std::string to_string() const {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!field.empty()) s += ": " + field;
    return s + ": " + message;
  }
};

// A value or the error that prevented it; std::expected arrives only with C++23.
template <typename T>
class Parsed {
 public:
  Parsed(T value) : v_(std::move(value)) {}
  Parsed(ParseError error) : v_(std::move(error)) {}
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() { return std::get<0>(v_); }
  const T& value() const { return std::get<0>(v_); }
  const ParseError& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, ParseError> v_;
};

}  // namespace roadload
