#pragma once
// Each subcommand of `roadload` is one entry in a table: a name, a one-line summary and a function.
#include <span>
#include <string_view>

#include "roadload/parse_error.hpp"

namespace roadload::cli {

using Args = std::span<char* const>;  // arguments after the subcommand name

struct Command {
  std::string_view name;
  std::string_view summary;
  int (*run)(Args args);
};

int run_decode(Args args);
int run_simulate(Args args);
int run_analyze(Args args);
int run_calibrate(Args args);
int run_grade(Args args);
int run_psd(Args args);
int run_replay(Args args);
int run_report(Args args);
int run_gap(Args args);
int run_route(Args args);
int run_vehicle(Args args);

// Exit codes, as sysexits.h names them.
inline constexpr int kExitOk = 0;
inline constexpr int kExitDataErr = 65;  // input was read but some of it was malformed
inline constexpr int kExitUsage = 64;
inline constexpr int kExitNoInput = 66;
inline constexpr int kExitCantCreate = 73;  // an output file could not be written
inline constexpr int kExitNoPerm = 77;      // an operation needed a privilege the process lacks

// A file that was read and found malformed (its error names a line) is bad data; one that could
// not be opened or read at all is missing input.
inline int exit_for(const ParseError& e) { return e.line > 0 ? kExitDataErr : kExitNoInput; }

}  // namespace roadload::cli
