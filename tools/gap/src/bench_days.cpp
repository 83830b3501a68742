#include <filesystem>

#include "roadload/gap/bench.hpp"
#include "roadload/sim/units.hpp"
#include "roadload/toml_fields.hpp"

namespace roadload::gap {
namespace {

// One run of a day: the model it names, and the drive as that model with the day's weather and,
// for a cruise, its own speed.
void read_run(const detail::TomlFields& f, const toml::table& t, const std::string& where, const std::string& data_dir,
              BenchDay& day) {
  f.only(t,
         {"label", "scenario", "mode", "speed_mph", "duration_s", "driven_before_s", "air_temp_c", "wind_speed_mps", "wind_from_deg"},
         where);
  const std::string label = f.required_text(t, "label", where);
  const std::string name = f.required_text(t, "scenario", where);
  auto loaded = sim::load_scenario(name, data_dir);
  if (!loaded) throw detail::TomlFailure{loaded.error()};
  sim::Scenario model = std::move(loaded.value());
  if (const auto mode = f.text(t, "mode", where)) {
    if (*mode != "coast" && *mode != "cruise") f.fail(t.get("mode"), where + "mode", "expected \"cruise\" or \"coast\"");
    if (*mode == "coast") {
      model.coast = true;
      model.stops = {};
    }
  }
  if (t.contains("duration_s")) model.duration = Seconds{f.required_in(t, "duration_s", where, 10.0, 7200.0)};
  sim::Scenario drive = model;
  if (t.contains("speed_mph")) {
    if (model.coast) f.fail(t.get("speed_mph"), where + "speed_mph", "a coast-down starts at its scenario's speed");
    drive.speed_mps = f.required_in(t, "speed_mph", where, 5.0, 85.0) * sim::kMps_per_mph;
  }
  // Each given field within its physical range (NaN included in what is refused); the model's otherwise.
  auto set_in = [&](std::string_view key, double lo, double hi, double& value) {
    if (t.contains(key)) value = f.required_in(t, key, where, lo, hi);
  };
  set_in("air_temp_c", -40.0, 50.0, drive.weather.air_temp_c);
  double driven_s = drive.driven_before.count();
  set_in("driven_before_s", 0.0, sim::kMaxDrivenBefore.count(), driven_s);
  drive.driven_before = Seconds{driven_s};
  set_in("wind_speed_mps", 0.0, 25.0, drive.weather.wind_speed_mps);
  set_in("wind_from_deg", 0.0, 360.0, drive.weather.wind_from_deg);
  day.labels.push_back(label);
  day.models.push_back(std::move(model));
  day.drives.push_back(std::move(drive));
}

}  // namespace

Parsed<std::vector<BenchDay>> load_bench_days(const std::string& path, const std::string& data_dir) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const detail::TomlFields f(path);
  try {
    const toml::table& root = parsed.value();
    f.only(root, {"day"}, "");
    const toml::array* days = root["day"].as_array();
    if (days == nullptr || days->empty()) f.fail(&root, "day", "no [[day]] tables");
    std::vector<BenchDay> out;
    for (const toml::node& d : *days) {
      const toml::table* t = d.as_table();
      if (t == nullptr) f.fail(&d, "day", "expected [[day]] tables");
      f.only(*t, {"road", "run"}, "day.");
      BenchDay& day = out.emplace_back();
      day.road = f.required_text(*t, "road", "day.");
      const toml::array* runs = (*t)["run"].as_array();
      if (runs == nullptr || runs->empty()) f.fail(t, "day.run", "a day needs at least one [[day.run]]");
      for (const toml::node& r : *runs) {
        if (!r.is_table()) f.fail(&r, "day.run", "expected [[day.run]] tables");
        read_run(f, *r.as_table(), "day.run.", data_dir, day);
      }
    }
    return out;
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
}

std::string default_bench_days(const std::string& data_dir) {
  return (std::filesystem::path(data_dir) / "bench" / "test-days.toml").string();
}

}  // namespace roadload::gap
