#include "roadload/vehicle_file.hpp"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/vehicle_table.hpp"
#include "vehicle_fields.hpp"

namespace roadload {
namespace {

using detail::TomlFields;
using vehicle_fields::NumberField;
namespace vf = vehicle_fields;

const toml::table& section(const TomlFields& f, const toml::table& root, std::string_view name, const std::string& where) {
  const toml::node* n = root.get(name);
  if (n == nullptr) f.fail(&root, where + std::string(name), "required table [" + where + std::string(name) + "] missing");
  if (!n->is_table()) f.fail(n, where + std::string(name), "expected a table");
  return *n->as_table();
}

template <typename T, std::size_t N>
void add_keys(std::vector<std::string_view>& keys, const NumberField<T> (&fields)[N]) {
  for (const NumberField<T>& n : fields) keys.emplace_back(n.key);
}

template <typename T, std::size_t N>
void read_fields(const TomlFields& f, const toml::table& t, const std::string& where, const NumberField<T> (&fields)[N], T& out) {
  for (const NumberField<T>& n : fields) out.*n.member = f.required_in(t, n.key, where, n.lo, n.hi);
}

// A section of plain numbers only: any other key is an error.
template <typename T, std::size_t N>
void read_numbers(const TomlFields& f, const toml::table& t, const std::string& where, const NumberField<T> (&fields)[N], T& out) {
  std::vector<std::string_view> keys;
  add_keys(keys, fields);
  f.only(t, keys, where);
  read_fields(f, t, where, fields, out);
}

VehicleAxle read_axle(const TomlFields& f, const toml::table& t, const std::string& where) {
  std::vector<std::string_view> keys{"name", "unit", "tires", "driven", "axle_mount", "frame_mount"};
  add_keys(keys, vf::kAxle);
  add_keys(keys, vf::kSuspension);
  f.only(t, keys, where);
  VehicleAxle a;
  a.name = f.required_text(t, "name", where);
  a.unit = f.required_text(t, "unit", where);
  read_fields(f, t, where, vf::kAxle, a);
  read_fields(f, t, where, vf::kSuspension, a.suspension);
  if (a.unsprung_kg > a.load_kg) f.fail(t.get("unsprung_kg"), where + "unsprung_kg", "more than the axle's load_kg");
  if (a.report_unsprung_kg > a.load_kg)
    f.fail(t.get("report_unsprung_kg"), where + "report_unsprung_kg", "more than the axle's load_kg");
  a.tires = static_cast<int>(f.required_in(t, "tires", where, 1, vf::kMaxTires));
  a.driven = f.flag(t, "driven", where).value_or(false);
  a.axle_mount = f.required_text(t, "axle_mount", where);
  a.frame_mount = f.required_text(t, "frame_mount", where);
  return a;
}

AccelerometerMount read_accelerometer(const TomlFields& f, const toml::table& t, const std::string& where, const Vehicle& v) {
  std::vector<std::string_view> keys{"name", "position", "axle", "on_axle"};
  add_keys(keys, vf::kAccelerometer);
  f.only(t, keys, where);
  AccelerometerMount m;
  m.name = f.required_text(t, "name", where);
  m.position = f.required_text(t, "position", where);
  m.axle = f.required_text(t, "axle", where);
  if (v.axle(m.axle) == nullptr) f.fail(t.get("axle"), where + "axle", "no [[axle]] named '" + m.axle + "'");
  m.on_axle = f.flag(t, "on_axle", where).value_or(false);
  read_fields(f, t, where, vf::kAccelerometer, m);
  return m;
}

template <typename T, typename Read>
std::vector<T> read_array(const TomlFields& f, const toml::table& root, std::string_view key, const std::string& where, Read read) {
  std::vector<T> out;
  const toml::node* n = root.get(key);
  if (n == nullptr) return out;
  const toml::array* items = n->as_array();
  if (items == nullptr) f.fail(n, where + std::string(key), "expected [[" + std::string(key) + "]] tables");
  for (std::size_t i = 0; i < items->size(); ++i) {
    const std::string item = where + std::string(key) + "[" + std::to_string(i) + "].";
    const toml::table* t = (*items)[i].as_table();
    if (t == nullptr) f.fail(&(*items)[i], item, "expected a table");
    out.push_back(read(*t, item));
  }
  return out;
}

void read_engine(const TomlFields& f, const toml::table& t, const std::string& w, EngineDescription& e) {
  std::vector<std::string_view> keys{"full_load_rpm", "full_load_fraction"};
  add_keys(keys, vf::kEngine);
  f.only(t, keys, w);
  read_fields(f, t, w, vf::kEngine, e);
  e.full_load_rpm = f.required_numbers(t, "full_load_rpm", w, 0, vf::kMaxMapRpm);
  e.full_load_fraction = f.required_numbers(t, "full_load_fraction", w, 0, vf::kMaxFullLoadFraction);
  if (e.full_load_rpm.size() != vf::kMapPoints) f.fail(t.get("full_load_rpm"), w + "full_load_rpm", "expected EC1's 6 map points");
  if (e.full_load_fraction.size() != vf::kMapPoints) {
    f.fail(t.get("full_load_fraction"), w + "full_load_fraction", "expected EC1's 6 map points");
  }
}

void read_driveline(const TomlFields& f, const toml::table& t, const std::string& w, DrivelineDescription& d) {
  std::vector<std::string_view> keys{"gear_ratios", "shift_time_s"};
  add_keys(keys, vf::kDriveline);
  f.only(t, keys, w);
  read_fields(f, t, w, vf::kDriveline, d);
  d.gear_ratios = f.required_numbers(t, "gear_ratios", w, vf::kMinGearRatio, vf::kMaxGearRatio);
  if (d.gear_ratios.empty()) f.fail(t.get("gear_ratios"), w + "gear_ratios", "at least one gear");
  d.shift_time = Seconds{f.required_in(t, "shift_time_s", w, 0, vf::kMaxShiftTime_s)};
}

// Axles front to rear, distinct names, at least one driven.
void check_axles(const TomlFields& f, const toml::table& root, const std::string& where, const Vehicle& v) {
  const toml::node* axles = root.get("axle");
  if (v.axles.empty()) f.fail(&root, where + "axle", "at least one [[axle]] table required");
  for (std::size_t i = 1; i < v.axles.size(); ++i) {
    const std::string item = where + "axle[" + std::to_string(i) + "].";
    if (v.axles[i].position_m < v.axles[i - 1].position_m) f.fail(axles, item + "position_m", "axles go front to rear");
    for (std::size_t j = 0; j < i; ++j) {
      if (v.axles[i].name == v.axles[j].name) f.fail(axles, item + "name", "repeats an axle's name");
    }
  }
  if (v.drive_axle() == nullptr) f.fail(axles, where + "axle", "no axle is driven");
}

}  // namespace

namespace detail {

Vehicle read_vehicle(const TomlFields& f, const toml::table& root, const std::string& w) {
  f.only(root, {"name", "description", "vin", "body", "engine", "driveline", "fuel", "accessories", "axle", "accelerometer"}, w);
  Vehicle v;
  v.name = f.required_text(root, "name", w);
  v.description = f.text(root, "description", w).value_or("");
  v.vin = f.text(root, "vin", w).value_or("");
  const toml::table& body = section(f, root, "body", w);
  std::vector<std::string_view> body_keys;
  add_keys(body_keys, vf::kBody);
  add_keys(body_keys, vf::kBodyOptional);
  f.only(body, body_keys, w + "body.");
  read_fields(f, body, w + "body.", vf::kBody, v);
  for (const auto& n : vf::kBodyOptional) {
    if (body.contains(n.key)) v.*n.member = f.required_in(body, n.key, w + "body.", n.lo, n.hi);
  }
  read_engine(f, section(f, root, "engine", w), w + "engine.", v.engine);
  read_driveline(f, section(f, root, "driveline", w), w + "driveline.", v.driveline);
  read_numbers(f, section(f, root, "fuel", w), w + "fuel.", vf::kFuel, v.fuel);
  read_numbers(f, section(f, root, "accessories", w), w + "accessories.", vf::kAccessories, v.accessories);
  v.axles = read_array<VehicleAxle>(f, root, "axle", w,
                                    [&](const toml::table& t, const std::string& i) { return read_axle(f, t, i); });
  check_axles(f, root, w, v);
  v.accelerometers = read_array<AccelerometerMount>(
      f, root, "accelerometer", w, [&](const toml::table& t, const std::string& i) { return read_accelerometer(f, t, i, v); });
  return v;
}

}  // namespace detail

Parsed<Vehicle> load_vehicle_file(const std::string& path) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  try {
    Vehicle v = detail::read_vehicle(TomlFields(path), parsed.value(), "");
    v.source = path;
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
