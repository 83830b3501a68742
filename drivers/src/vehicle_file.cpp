#include "roadload/vehicle_file.hpp"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <limits>

#include "roadload/definitions.hpp"
#include "roadload/toml_fields.hpp"

namespace roadload {
namespace {

using detail::TomlFields;

const toml::table& section(const TomlFields& f, const toml::table& root, std::string_view name) {
  const toml::table* t = f.table(root, name);
  if (t == nullptr) f.fail(&root, std::string(name), "required table [" + std::string(name) + "] missing");
  return *t;
}

VehicleAxle read_axle(const TomlFields& f, const toml::table& t, const std::string& where) {
  f.only(
      t,
      {"name", "unit", "position_m", "load_kg", "unsprung_kg", "report_unsprung_kg", "tires", "tire_radius_m", "wheel_inertia_kgm2",
       "driven", "spring_npm", "damper_nspm", "tire_stiffness_npm", "tire_damping_nspm", "axle_mount", "frame_mount"},
      where);
  VehicleAxle a;
  a.name = f.required_text(t, "name", where);
  a.unit = f.required_text(t, "unit", where);
  a.position_m = f.required_in(t, "position_m", where, 0, 50);
  a.load_kg = f.required_in(t, "load_kg", where, 1, 50000);
  a.unsprung_kg = f.required_in(t, "unsprung_kg", where, 1, a.load_kg);
  a.report_unsprung_kg = f.required_in(t, "report_unsprung_kg", where, 1, a.load_kg);
  a.tires = static_cast<int>(f.required_in(t, "tires", where, 1, 8));
  a.tire_radius_m = f.required_in(t, "tire_radius_m", where, 0.2, 1.0);
  a.wheel_inertia_kgm2 = f.required_in(t, "wheel_inertia_kgm2", where, 0, 1000);
  a.driven = f.flag(t, "driven", where).value_or(false);
  a.suspension.spring_npm = f.required_in(t, "spring_npm", where, 1e3, 1e8);
  a.suspension.damper_nspm = f.required_in(t, "damper_nspm", where, 0, 1e7);
  a.suspension.tire_stiffness_npm = f.required_in(t, "tire_stiffness_npm", where, 1e4, 1e9);
  a.suspension.tire_damping_nspm = f.required_in(t, "tire_damping_nspm", where, 0, 1e7);
  a.axle_mount = f.required_text(t, "axle_mount", where);
  a.frame_mount = f.required_text(t, "frame_mount", where);
  return a;
}

AccelerometerMount read_accelerometer(const TomlFields& f, const toml::table& t, const std::string& where, const Vehicle& v) {
  f.only(t, {"name", "position", "axle", "on_axle", "range_g"}, where);
  AccelerometerMount m;
  m.name = f.required_text(t, "name", where);
  m.position = f.required_text(t, "position", where);
  m.axle = f.required_text(t, "axle", where);
  if (v.axle(m.axle) == nullptr) f.fail(t.get("axle"), where + "axle", "no [[axle]] named '" + m.axle + "'");
  m.on_axle = f.flag(t, "on_axle", where).value_or(false);
  m.range_g = f.required_in(t, "range_g", where, 0.1, 1000);
  return m;
}

template <typename T, typename Read>
std::vector<T> read_array(const TomlFields& f, const toml::table& root, std::string_view key, Read read) {
  std::vector<T> out;
  const toml::array* items = root[key].as_array();
  if (items == nullptr) return out;
  for (std::size_t i = 0; i < items->size(); ++i) {
    const std::string where = std::string(key) + "[" + std::to_string(i) + "].";
    const toml::table* t = (*items)[i].as_table();
    if (t == nullptr) f.fail(&(*items)[i], where, "expected a table");
    out.push_back(read(*t, where));
  }
  return out;
}

void read_engine(const TomlFields& f, const toml::table& t, EngineDescription& e) {
  const std::string w = "engine.";
  f.only(t,
         {"reference_torque_nm", "idle_rpm", "inertia_kgm2", "full_load_rpm", "full_load_fraction", "friction_a_pct",
          "friction_b_pct", "friction_c_pct"},
         w);
  e.reference_torque_nm = f.required_in(t, "reference_torque_nm", w, 1, 64255);  // SPN 544's range
  e.idle_rpm = f.required_in(t, "idle_rpm", w, 100, 3000);
  e.inertia_kgm2 = f.required_in(t, "inertia_kgm2", w, 0, 100);
  e.full_load_rpm = f.required_numbers(t, "full_load_rpm", w, 0, 8031.875);  // SPN 188's range
  e.full_load_fraction = f.required_numbers(t, "full_load_fraction", w, 0, 1.25);
  // EC1's map: idle, four points and high idle.
  if (e.full_load_rpm.size() != 6) f.fail(t.get("full_load_rpm"), w + "full_load_rpm", "expected EC1's 6 map points");
  if (e.full_load_fraction.size() != 6) {
    f.fail(t.get("full_load_fraction"), w + "full_load_fraction", "expected EC1's 6 map points");
  }
  e.friction_a_pct = f.required_in(t, "friction_a_pct", w, 0, 100);
  e.friction_b_pct = f.required_in(t, "friction_b_pct", w, 0, 100);
  e.friction_c_pct = f.required_in(t, "friction_c_pct", w, 0, 100);
}

void read_driveline(const TomlFields& f, const toml::table& t, DrivelineDescription& d) {
  const std::string w = "driveline.";
  f.only(t, {"gear_ratios", "final_drive", "efficiency", "inertia_kgm2", "shift_time_s"}, w);
  d.gear_ratios = f.required_numbers(t, "gear_ratios", w, 0.1, 30);
  if (d.gear_ratios.empty()) f.fail(t.get("gear_ratios"), w + "gear_ratios", "at least one gear");
  d.final_drive = f.required_in(t, "final_drive", w, 0.5, 20);
  d.efficiency = f.required_in(t, "efficiency", w, 0.5, 1);
  d.inertia_kgm2 = f.required_in(t, "inertia_kgm2", w, 0, 100);
  d.shift_time = Seconds{f.required_in(t, "shift_time_s", w, 0, 10)};
}

// A section of plain numbers: each key, the member it fills and the range that is physical.
template <typename T>
struct NumberField {
  const char* key;
  double T::*member;
  double lo, hi;
};

template <typename T, std::size_t N>
void read_numbers(const TomlFields& f, const toml::table& t, const std::string& where, const NumberField<T> (&fields)[N], T& out) {
  for (const auto& [key, node] : t) {
    const std::string_view name = key.str();  // a structured binding cannot be captured before C++20's clang 16
    const auto known = std::find_if(std::begin(fields), std::end(fields), [name](const auto& n) { return name == n.key; });
    if (known == std::end(fields)) f.fail(&node, where + std::string(name), "unknown key");
  }
  for (const NumberField<T>& n : fields) out.*n.member = f.required_in(t, n.key, where, n.lo, n.hi);
}

constexpr NumberField<FuelDescription> kFuelFields[] = {
    {"eta_indicated_max", &FuelDescription::eta_indicated_max, 0.05, 0.7},
    {"n_opt_rpm", &FuelDescription::n_opt_rpm, 100, 8000},
    {"eta_speed_coeff", &FuelDescription::eta_speed_coeff, 0, 1},
    {"lhv_jpkg", &FuelDescription::lhv_jpkg, 1e6, 1.5e8},
    {"density_kgpl", &FuelDescription::density_kgpl, 0.1, 2},
};

constexpr NumberField<AccessoryDescription> kAccessoryFields[] = {
    {"alternator_w", &AccessoryDescription::alternator_w, 0, 1e5},  {"steering_w", &AccessoryDescription::steering_w, 0, 1e5},
    {"compressor_w", &AccessoryDescription::compressor_w, 0, 1e5},  {"fan_engaged_w", &AccessoryDescription::fan_engaged_w, 0, 2e5},
    {"fan_ref_rpm", &AccessoryDescription::fan_ref_rpm, 100, 8000}, {"fan_idle_w", &AccessoryDescription::fan_idle_w, 0, 1e5},
};

constexpr NumberField<Vehicle> kBodyFields[] = {
    {"cda_m2", &Vehicle::cda_m2, 0.5, 30},
    {"cda_sigma_m2", &Vehicle::cda_sigma_m2, 0, 10},
    {"gnss_antenna_behind_front_m", &Vehicle::gnss_antenna_behind_front_m, -5, 50},
    {"gnss_antenna_height_m", &Vehicle::gnss_antenna_height_m, 0, 10},
};

// Axles front to rear, distinct names, at least one driven.
void check_axles(const TomlFields& f, const toml::table& root, const Vehicle& v) {
  const toml::node* axles = root.get("axle");
  if (v.axles.empty()) f.fail(&root, "axle", "at least one [[axle]] table required");
  for (std::size_t i = 1; i < v.axles.size(); ++i) {
    if (v.axles[i].position_m < v.axles[i - 1].position_m) {
      f.fail(axles, "axle[" + std::to_string(i) + "].position_m", "axles go front to rear");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (v.axles[i].name == v.axles[j].name) f.fail(axles, "axle[" + std::to_string(i) + "].name", "repeats an axle's name");
    }
  }
  if (v.drive_axle() == nullptr) f.fail(axles, "axle", "no axle is driven");
}

}  // namespace

Parsed<Vehicle> load_vehicle_file(const std::string& path) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const toml::table& root = parsed.value();
  TomlFields f(path);
  try {
    f.only(root, {"name", "description", "vin", "body", "engine", "driveline", "fuel", "accessories", "axle", "accelerometer"}, "");
    Vehicle v;
    v.source = path;
    v.name = f.required_text(root, "name", "");
    v.description = f.text(root, "description", "").value_or("");
    v.vin = f.text(root, "vin", "").value_or("");
    read_numbers(f, section(f, root, "body"), "body.", kBodyFields, v);
    read_engine(f, section(f, root, "engine"), v.engine);
    read_driveline(f, section(f, root, "driveline"), v.driveline);
    read_numbers(f, section(f, root, "fuel"), "fuel.", kFuelFields, v.fuel);
    read_numbers(f, section(f, root, "accessories"), "accessories.", kAccessoryFields, v.accessories);
    v.axles = read_array<VehicleAxle>(f, root, "axle",
                                      [&](const toml::table& t, const std::string& w) { return read_axle(f, t, w); });
    check_axles(f, root, v);
    v.accelerometers = read_array<AccelerometerMount>(
        f, root, "accelerometer", [&](const toml::table& t, const std::string& w) { return read_accelerometer(f, t, w, v); });
    return v;
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
}

std::string resolve_vehicle(const std::string& name_or_path, const std::string& dir) {
  if (std::filesystem::exists(name_or_path)) return name_or_path;
  return dir + "/vehicles/" + name_or_path + ".toml";
}

std::string resolve_vehicle(const std::string& name_or_path) { return resolve_vehicle(name_or_path, data_dir()); }

std::string default_vehicle_path() { return resolve_vehicle(kDefaultVehicle); }

}  // namespace roadload
