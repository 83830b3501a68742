#pragma once
// A --route argument: a route file, or the name of a built-in route (config/routes/NAME.toml).
#include <string>

namespace roadload::cli {

std::string resolve_route(const std::string& name_or_path);

}  // namespace roadload::cli
