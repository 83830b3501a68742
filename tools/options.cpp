#include "options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "roadload/definitions.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::cli {

bool OptionParser::flag(std::string_view a, std::string_view b) {
  if (!more()) return false;
  if (current() != a && (b.empty() || current() != b)) return false;
  ++pos_;
  return true;
}

bool OptionParser::help(const char* text) {
  if (!flag("-h", "--help")) return false;
  std::fputs(text, stdout);
  return true;
}

std::optional<std::string_view> OptionParser::value(std::string_view name) {
  if (!more()) return std::nullopt;
  const std::string_view arg = current();
  if (arg.size() > name.size() && arg.substr(0, name.size()) == name && arg[name.size()] == '=') {
    ++pos_;
    return arg.substr(name.size() + 1);
  }
  if (arg != name) return std::nullopt;
  if (pos_ + 1 >= args_.size()) {
    fail(std::string(name) + " needs a value");
    return std::nullopt;
  }
  pos_ += 2;
  return std::string_view(args_[pos_ - 1]);
}

std::optional<std::int64_t> OptionParser::number(std::string_view name, std::int64_t min, std::int64_t max) {
  const auto v = value(name);
  if (!v) return std::nullopt;
  std::string_view s = *v;
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    s.remove_prefix(2);
    base = 16;
  }
  std::int64_t n = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), n, base);
  if (ec != std::errc() || end != s.data() + s.size() || n < min || n > max) {
    fail(std::string(name) + ": '" + std::string(*v) + "' is not a whole number in " + std::to_string(min) + ".." +
         std::to_string(max));
    return std::nullopt;
  }
  return n;
}

std::optional<double> OptionParser::real(std::string_view name, double min, double max) {
  const auto v = value(name);
  if (!v) return std::nullopt;
  double d = 0;
  const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), d);
  if (ec != std::errc() || end != v->data() + v->size() || !std::isfinite(d) || d < min || d > max) {
    fail(std::string(name) + ": '" + std::string(*v) + "' is not a finite number in " + std::to_string(min) + ".." +
         std::to_string(max));
    return std::nullopt;
  }
  return d;
}

std::optional<std::string_view> OptionParser::positional() {
  if (!more()) return std::nullopt;
  const std::string_view arg = current();
  if (arg.size() > 1 && arg[0] == '-') return std::nullopt;
  ++pos_;
  return arg;
}

bool OptionParser::single_positional(std::string& into, std::string_view what) {
  const auto arg = positional();
  if (!arg) return false;
  if (!into.empty()) {
    fail("one " + std::string(what) + " at a time: '" + into + "' and '" + std::string(*arg) + "' given");
    return true;
  }
  into = *arg;
  return true;
}

int OptionParser::fail(const std::string& message) {
  if (!failed_)
    std::fprintf(stderr, "roadload %.*s: %s (see --help)\n", static_cast<int>(command_.size()), command_.data(), message.c_str());
  failed_ = true;
  return kExitUsage;
}

int OptionParser::fail_unknown() { return fail("unknown option '" + std::string(current()) + "'"); }

std::optional<int> load_definitions(std::string_view command, const std::vector<std::string>& extra, j1939::Database& db) {
  std::vector<std::string> paths{core_dbc_path()};
  paths.insert(paths.end(), extra.begin(), extra.end());
  for (const std::string& path : paths) {
    if (auto err = load_dbc_file(db, path)) {
      std::fprintf(stderr, "roadload %.*s: %s\n", static_cast<int>(command.size()), command.data(), err->to_string().c_str());
      return exit_for(*err);
    }
  }
  return std::nullopt;
}

std::variant<LoadedRoute, int> load_route(std::string_view command, const std::string& name) {
  const int n = static_cast<int>(command.size());
  auto route = load_route_file(resolve_route(name));
  if (!route) {
    std::fprintf(stderr, "roadload %.*s: %s\n", n, command.data(), route.error().to_string().c_str());
    return exit_for(route.error());
  }
  auto geometry = RouteGeometry::build(route.value().points);
  if (!geometry) {
    std::fprintf(stderr, "roadload %.*s: %s: point: fewer than two distinct points\n", n, command.data(),
                 route.value().source_file.c_str());
    return kExitDataErr;
  }
  LoadedRoute loaded{std::move(route.value()), std::move(*geometry), std::nullopt};
  if (!loaded.file.grade_file.empty()) {
    auto grade = load_grade_file(loaded.file.grade_file, loaded.geometry.length_m());
    if (!grade) {
      std::fprintf(stderr, "roadload %.*s: %s\n", n, command.data(), grade.error().to_string().c_str());
      return exit_for(grade.error());
    }
    loaded.grade = std::move(grade.value());
  }
  return loaded;
}

std::variant<Vehicle, int> load_vehicle(std::string_view command, const std::string& name_or_path) {
  auto vehicle = load_vehicle_file(resolve_vehicle(name_or_path));
  if (vehicle) return std::move(vehicle.value());
  std::fprintf(stderr, "roadload %.*s: %s\n", static_cast<int>(command.size()), command.data(), vehicle.error().to_string().c_str());
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

std::optional<int> expect_action(std::string_view command, Args args, std::string_view action, const char* help) {
  if (args.empty() || std::string_view(args[0]) == "-h" || std::string_view(args[0]) == "--help") {
    std::fputs(help, args.empty() ? stderr : stdout);
    return args.empty() ? kExitUsage : kExitOk;
  }
  if (std::string_view(args[0]) == action) return std::nullopt;
  std::fprintf(stderr, "roadload %.*s: unknown action '%s' (expected: %.*s)\n", static_cast<int>(command.size()), command.data(),
               args[0], static_cast<int>(action.size()), action.data());
  return kExitUsage;
}

std::optional<int> write_text_file(std::string_view command, const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (out) return std::nullopt;
  std::fprintf(stderr, "roadload %.*s: %s: cannot write\n", static_cast<int>(command.size()), command.data(), path.c_str());
  return kExitCantCreate;
}

}  // namespace roadload::cli
