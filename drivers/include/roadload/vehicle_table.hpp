#pragma once
// A vehicle description read from a TOML table: a vehicle file's root, or the copy a recording's
// meta.toml carries under [vehicle.file]. For the readers of those files; others use
// vehicle_file.hpp.
#include <string>

#include "roadload/toml_fields.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::detail {

// Field names in errors start with `where` ("", "vehicle.file."); throws TomlFailure.
Vehicle read_vehicle(const TomlFields& f, const toml::table& root, const std::string& where);

}  // namespace roadload::detail
