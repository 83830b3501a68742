#pragma once
// roadloadd's command line: --config FILE, then overrides of the common settings.
#include <string>
#include <vector>

#include "roadload/firmware/config.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::firmware {

struct CommandLine {
  DaemonConfig config;
  std::string print;  // --help's or --version's text: printed on standard output, and nothing run
  bool print_config = false;
  bool exit_when_done = false;  // stop once every replayed stream has ended
};

// A usage error's field is the option at fault ("--can"); a bad file's, its key.
Parsed<CommandLine> parse_command_line(const std::vector<std::string>& args);

// The file an error of the command line itself names (not of a --config file or the settings).
inline constexpr const char* kCommandLineSource = "command line";
// Exit statuses, as sysexits.h names them: a bad command line, bad settings (which systemd is
// told not to restart on: the unit's RestartPreventExitStatus).
inline constexpr int kExitUsage = 64;
inline constexpr int kExitConfig = 78;

}  // namespace roadload::firmware
