#pragma once
// What every hand-written text parser here needs first: skip white space and keep counting lines,
// so each error names the line it is on.
#include <cstddef>
#include <string_view>

namespace roadload {

// The first position at or after `pos` that is not a space, tab, carriage return or newline; each
// newline passed adds one to `line`.
inline std::size_t skip_whitespace(std::string_view text, std::size_t pos, long& line) {
  for (; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (c == '\n') {
      ++line;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      break;
    }
  }
  return pos;
}

}  // namespace roadload
