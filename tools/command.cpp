#include "command.hpp"

#include <cstdio>

namespace roadload::cli {

int usage_error(std::string_view command, const std::string& message) {
  std::fprintf(stderr, "roadload%s%.*s: %s (see --help)\n", command.empty() ? "" : " ", static_cast<int>(command.size()),
               command.data(), message.c_str());
  return kExitUsage;
}

}  // namespace roadload::cli
