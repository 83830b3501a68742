#pragma once
// How every command ends and speaks: exit codes as sysexits.h names them, and its messages as
// "roadload COMMAND: text" on standard error. A library caller (the Python module) captures the
// same lines instead, so that an error it raises carries the words the command would have printed.
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"

namespace roadload::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitDataErr = 65;  // input was read but some of it was malformed
inline constexpr int kExitUsage = 64;
inline constexpr int kExitNoInput = 66;
inline constexpr int kExitCantCreate = 73;  // an output file could not be written
inline constexpr int kExitNoPerm = 77;      // an operation needed a privilege the process lacks

// A file that was read and found malformed (its error names a line) is bad data; one that could
// not be opened or read at all is missing input.
inline int exit_for(const ParseError& e) { return e.line > 0 ? kExitDataErr : kExitNoInput; }

// "roadload COMMAND: text" (or "roadload: text" without a command) on standard error, or into
// this thread's MessageCapture while one lives.
void say(std::string_view command, std::string_view text);

// Says the error as say() does; returns `status`, or the status exit_for() gives the error.
int failed(std::string_view command, const ParseError& e, int status);
inline int failed(std::string_view command, const ParseError& e) { return failed(command, e, exit_for(e)); }

// Prints "roadload COMMAND: message (see --help)" as say() does; returns kExitUsage. For what
// the options cannot say alone ("--aero and --torque-scale are separate calibrations"); CLI11
// reports the rest the same way.
int usage_error(std::string_view command, const std::string& message);

// While it lives, what say() is given on this thread is kept here, without the "roadload
// COMMAND: " prefix, and nothing is printed. Per thread, so that analyses running at once in
// one process (threads releasing Python's lock) keep their messages apart.
class MessageCapture {
 public:
  MessageCapture();
  ~MessageCapture();
  MessageCapture(const MessageCapture&) = delete;
  MessageCapture& operator=(const MessageCapture&) = delete;
  const std::vector<std::string>& lines() const { return lines_; }
  void add(std::string_view text) { lines_.emplace_back(text); }

 private:
  std::vector<std::string> lines_;
  MessageCapture* outer_;
};

}  // namespace roadload::cli
