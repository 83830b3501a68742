#pragma once
// A small option parser: each call looks at the current argument and consumes it on a match, so a
// command's loop reads like its --help. Accepts "--name value" and "--name=value".
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "command.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/route_file.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::cli {

class OptionParser {
 public:
  OptionParser(std::string_view command, Args args) : command_(command), args_(args) {}

  bool more() const { return !failed_ && pos_ < args_.size(); }
  bool failed() const { return failed_; }

  bool flag(std::string_view a, std::string_view b = {});
  // -h or --help: prints `text` to standard output.
  bool help(const char* text);
  std::optional<std::string_view> value(std::string_view name);
  std::optional<std::int64_t> number(std::string_view name, std::int64_t min, std::int64_t max);
  std::optional<double> real(std::string_view name, double min, double max);
  std::optional<std::string_view> positional();
  // A command's one positional argument (`what`, as its usage names it) into `into`: true when an
  // argument was taken, a second one failing with both named (64) rather than replacing the first.
  bool single_positional(std::string& into, std::string_view what);

  int fail(const std::string& message);
  int fail_unknown();

 private:
  std::string_view current() const { return args_[pos_]; }

  std::string_view command_;
  Args args_;
  std::size_t pos_ = 0;
  bool failed_ = false;
};

// A command whose first argument names its action (`roadload route build`): with no argument it
// prints `help` on standard error (64), with -h or --help on standard output (0), and refuses any
// action but `action` (64). nullopt: the action is the one expected; its options follow it.
std::optional<int> expect_action(std::string_view command, Args args, std::string_view action, const char* help);

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
