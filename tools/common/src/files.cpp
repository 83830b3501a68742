#include "files.hpp"

#include <fstream>

#include "roadload/definitions.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::cli {

std::optional<int> load_definitions(std::string_view command, const std::vector<std::string>& extra, j1939::Database& db) {
  std::vector<std::string> paths{core_dbc_path()};
  paths.insert(paths.end(), extra.begin(), extra.end());
  for (const std::string& path : paths) {
    if (auto err = load_dbc_file(db, path)) {
      say(command, err->to_string());
      return exit_for(*err);
    }
  }
  return std::nullopt;
}

std::variant<LoadedRoute, int> load_route(std::string_view command, const std::string& name) {
  auto route = load_route_file(resolve_route(name));
  if (!route) {
    say(command, route.error().to_string());
    return exit_for(route.error());
  }
  auto geometry = RouteGeometry::build(route.value().points);
  if (!geometry) {
    say(command, route.value().source_file + ": point: fewer than two distinct points");
    return kExitDataErr;
  }
  LoadedRoute loaded{std::move(route.value()), std::move(*geometry), std::nullopt};
  if (!loaded.file.grade_file.empty()) {
    auto grade = load_grade_file(loaded.file.grade_file, loaded.geometry.length_m());
    if (!grade) {
      say(command, grade.error().to_string());
      return exit_for(grade.error());
    }
    loaded.grade = std::move(grade.value());
  }
  return loaded;
}

std::variant<Vehicle, int> load_vehicle(std::string_view command, const std::string& name_or_path) {
  auto vehicle = load_vehicle_file(resolve_vehicle(name_or_path));
  if (vehicle) return std::move(vehicle.value());
  say(command, vehicle.error().to_string());
  return exit_for(vehicle.error());
}

std::variant<RecordingVehicle, int> recording_vehicle(std::string_view command, const recording::Metadata& meta,
                                                      const std::string& vehicle_option) {
  RecordingVehicle r;
  if (!vehicle_option.empty() || !meta.vehicle_file) {
    auto v = load_vehicle(command, vehicle_option.empty() ? std::string(kDefaultVehicle) : vehicle_option);
    if (const int* rc = std::get_if<int>(&v)) return *rc;
    r.vehicle = std::move(std::get<Vehicle>(v));
    if (vehicle_option.empty()) {
      r.assumed = "no vehicle file: neither --vehicle nor the recording's meta.toml describes the truck, so " + r.vehicle.source +
                  " was assumed";
    }
  } else {
    r.vehicle = *meta.vehicle_file;
  }
  r.vehicle = recording::vehicle_from_metadata(r.vehicle, meta);
  return r;
}

std::variant<std::vector<std::string>, int> one_drive(std::string_view command, const std::vector<std::string>& given) {
  auto joined = recording::join_segments(given);
  if (!joined) {
    return usage_error(command, joined.error().to_string());
  }
  return std::move(joined.value());
}

void tell_errors(std::string_view command, const std::string& path, const recording::ErrorLog& errors) {
  for (const ParseError& e : errors.kept()) say(command, e.to_string());
  if (errors.count() > errors.kept().size())
    say(command, path + ": ... and " + std::to_string(errors.count() - errors.kept().size()) + " more malformed lines");
}

std::optional<int> write_text_file(std::string_view command, const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (out) return std::nullopt;
  say(command, path + ": cannot write");
  return kExitCantCreate;
}

}  // namespace roadload::cli
