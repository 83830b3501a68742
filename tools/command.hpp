#pragma once
// Each subcommand of `roadload` adds itself to the program's command line, its options bound to
// settings of its own, and returns what runs it once the command line has been read (main.cpp).
#include <functional>
#include <string>
#include <string_view>

#include "roadload/parse_error.hpp"

namespace CLI {
class App;
}

namespace roadload::cli {

using Run = std::function<int()>;

Run add_decode(CLI::App& roadload);
Run add_analyze(CLI::App& roadload);
Run add_calibrate(CLI::App& roadload);
Run add_collect(CLI::App& roadload);
Run add_gap(CLI::App& roadload);
Run add_grade(CLI::App& roadload);
Run add_network(CLI::App& roadload);
Run add_psd(CLI::App& roadload);
Run add_replay(CLI::App& roadload);
Run add_report(CLI::App& roadload);
Run add_route(CLI::App& roadload);
Run add_simulate(CLI::App& roadload);
Run add_vehicle(CLI::App& roadload);

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

// Prints "roadload COMMAND: message (see --help)" on standard error; returns kExitUsage. For what
// the options cannot say alone ("--aero and --torque-scale are separate calibrations"); CLI11
// reports the rest the same way.
int usage_error(std::string_view command, const std::string& message);

}  // namespace roadload::cli
