#include "route_arg.hpp"

#include <filesystem>

#include "roadload/definitions.hpp"

namespace roadload::cli {

std::string resolve_route(const std::string& name_or_path) {
  if (std::filesystem::exists(name_or_path)) return name_or_path;
  return data_dir() + "/routes/" + name_or_path + ".toml";
}

}  // namespace roadload::cli
