#pragma once
// A vehicle file (config/vehicles/*.toml; docs/vehicle-file.md): one truck's description, each
// value with its source in the file. Every number is checked finite and physical; an error names
// file, line and field.
#include <string>

#include "roadload/parse_error.hpp"
#include "roadload/vehicle.hpp"

namespace roadload {

// The vehicle a recording or a scenario is taken to be when it names none: the seed report's truck.
inline constexpr const char* kDefaultVehicle = "mnroad-truck";

Parsed<Vehicle> load_vehicle_file(const std::string& path);
// A vehicle argument: a file, or the name of a built-in vehicle (DATA_DIR/vehicles/NAME.toml;
// data_dir() when none is given).
std::string resolve_vehicle(const std::string& name_or_path, const std::string& data_dir);
std::string resolve_vehicle(const std::string& name_or_path);
std::string default_vehicle_path();

}  // namespace roadload
