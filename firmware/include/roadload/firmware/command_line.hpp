#pragma once
// roadloadd's command line: --config FILE, then overrides of the common settings.
#include <string>
#include <vector>

#include "roadload/firmware/config.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::firmware {

struct CommandLine {
  DaemonConfig config;
  bool help = false;
  bool version = false;
  bool print_config = false;
  bool exit_when_done = false;  // stop once every replayed stream has ended
};

extern const char* const kUsage;

Parsed<CommandLine> parse_command_line(const std::vector<std::string>& args);

}  // namespace roadload::firmware
