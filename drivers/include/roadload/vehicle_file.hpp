#pragma once
// A vehicle file (config/vehicles/*.toml; docs/vehicle-file.md): one truck's description, each
// value with its source in the file. Every number is checked finite and physical; an error names
// file, line and field.
#include <map>
#include <string>
#include <string_view>

#include "roadload/parse_error.hpp"
#include "roadload/vehicle.hpp"

namespace roadload {

// The vehicle a recording or a scenario is taken to be when it names none: the seed report's truck.
inline constexpr const char* kDefaultVehicle = "mnroad-truck";

Parsed<Vehicle> load_vehicle_file(const std::string& path);

// Why a value is what it is, by field ("engine.reference_torque_nm", "axle[1].tire_radius_m"):
// each is written as a comment above its key.
using VehicleNotes = std::map<std::string, std::string>;
// A vehicle file's text for this vehicle. Under a `table` ("vehicle.file") every key and table is
// nested there, as a recording's meta.toml carries the vehicle it was made with.
std::string format_vehicle(const Vehicle& v, const VehicleNotes& notes = {}, std::string_view table = "");
// A vehicle argument: a file, or the name of a built-in vehicle (DATA_DIR/vehicles/NAME.toml;
// data_dir() when none is given).
std::string resolve_vehicle(const std::string& name_or_path, const std::string& data_dir);
std::string resolve_vehicle(const std::string& name_or_path);
std::string default_vehicle_path();

}  // namespace roadload
