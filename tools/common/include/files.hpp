#pragma once
// The files every command reads, or writes whole, the same way: each failure printed as
// "roadload COMMAND: file:line: field: message" and given as the exit status.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "roadload/grade_profile.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/route_file.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/vehicle.hpp"
#include "status.hpp"

namespace roadload::recording {
class ErrorLog;
}

namespace roadload::cli {

// The recordings a command was given, as one drive: one as it is; several joined in order when
// they are the segments of one logger run (recording::join_segments). Anything else prints why
// and returns the usage status (64), rather than reading only some of them.
std::variant<std::vector<std::string>, int> one_drive(std::string_view command, const std::vector<std::string>& given);
// `given` replaced by its drive's segments in order, then `run()`; or the usage status.
template <typename Run>
int on_one_drive(std::string_view command, std::vector<std::string>& given, Run&& run) {
  auto drive = one_drive(command, given);
  if (const int* rc = std::get_if<int>(&drive)) return *rc;
  given = std::get<std::vector<std::string>>(std::move(drive));
  return run();
}

// Each malformed line a read kept, then how many more there were, said as the command's.
void tell_errors(std::string_view command, const std::string& path, const recording::ErrorLog& errors);

// Writes `text` to `path` whole; on failure prints "roadload COMMAND: path: cannot write" and
// returns the exit code (73).
std::optional<int> write_text_file(std::string_view command, const std::string& path, const std::string& text);

// The built-in J1939 definitions, then each of `extra` (--dbc) over them; on failure the error is
// printed as "roadload COMMAND: file:line: field: message" and the exit code returned.
std::optional<int> load_definitions(std::string_view command, const std::vector<std::string>& extra, j1939::Database& db);

// A route file or built-in route name with its geometry; on failure the error is printed as above
// and the exit code returned (66: no such route, 65: too few points).
// A route and, when its file names one (`grade`), its own grade profile with the profile's sigma:
// every command that runs the force balance on the route weighs its grade the same way.
struct LoadedRoute {
  RouteFile file;
  RouteGeometry geometry;
  std::optional<GradeProfile> grade;
};
std::variant<LoadedRoute, int> load_route(std::string_view command, const std::string& name);

// A vehicle file or built-in vehicle name (--vehicle); on failure the error is printed as above and
// the exit code returned (66: no such file, 65: a bad value in it).
std::variant<Vehicle, int> load_vehicle(std::string_view command, const std::string& name_or_path);

// The vehicle a recording was made with: --vehicle when given, else the vehicle file its meta.toml
// carries, with what meta.toml states of this drive over it. A recording that describes no truck
// is analysed as the default vehicle, and `assumed` says so: nothing from it is identified.
struct RecordingVehicle {
  Vehicle vehicle;
  std::string assumed;  // empty when the truck is described
};
std::variant<RecordingVehicle, int> recording_vehicle(std::string_view command, const recording::Metadata& meta,
                                                      const std::string& vehicle_option);

}  // namespace roadload::cli
