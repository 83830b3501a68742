// A vehicle description written back as a vehicle file: what `roadload vehicle identify` writes
// and what a recording's meta.toml carries. Every number is printed in its shortest exact form, so
// reading the text back gives the same vehicle.
#include <charconv>
#include <sstream>

#include "roadload/results/json.hpp"
#include "roadload/toml_text.hpp"
#include "roadload/vehicle_file.hpp"
#include "vehicle_fields.hpp"

namespace roadload {
namespace {

using vehicle_fields::NumberField;
namespace vf = vehicle_fields;

std::string number(double v) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : std::string("0");
}

// A TOML basic string escapes as a JSON string does: quotes, backslashes, control characters as \uXXXX.

class Writer {
 public:
  Writer(const VehicleNotes& notes, std::string_view table) : notes_(notes), table_(table) {}

  void header(std::string_view name, bool array = false) {
    const std::string full = table_.empty() ? std::string(name) : table_ + (name.empty() ? "" : "." + std::string(name));
    if (full.empty()) return;
    o_ << "\n" << (array ? "[[" : "[") << full << (array ? "]]" : "]") << "\n";
  }
  void key(const std::string& field, std::string_view key, const std::string& value) {
    if (auto it = notes_.find(field); it != notes_.end()) {
      std::istringstream lines(it->second);
      for (std::string line; std::getline(lines, line);) o_ << "# " << line << "\n";
    }
    o_ << key << " = " << value << "\n";
  }
  template <typename T, std::size_t N>
  void numbers(const std::string& where, const NumberField<T> (&fields)[N], const T& from) {
    for (const NumberField<T>& n : fields) key(where + n.key, n.key, number(from.*n.member));
  }
  void list(const std::string& where, std::string_view name, const std::vector<double>& values) {
    std::string text = "[";
    for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + number(values[i]);
    key(where + std::string(name), name, text + "]");
  }
  std::string text() const { return o_.str(); }

 private:
  const VehicleNotes& notes_;
  std::string table_;
  std::ostringstream o_;
};

void write_axle(Writer& w, const VehicleAxle& a, std::size_t i) {
  const std::string where = "axle[" + std::to_string(i) + "].";
  w.header("axle", true);
  w.key(where + "name", "name", toml_quoted(a.name));
  w.key(where + "unit", "unit", toml_quoted(a.unit));
  w.numbers(where, vf::kAxle, a);
  w.key(where + "tires", "tires", std::to_string(a.tires));
  w.key(where + "driven", "driven", a.driven ? "true" : "false");
  w.numbers(where, vf::kSuspension, a.suspension);
  w.key(where + "axle_mount", "axle_mount", toml_quoted(a.axle_mount));
  w.key(where + "frame_mount", "frame_mount", toml_quoted(a.frame_mount));
}

void write_accelerometer(Writer& w, const AccelerometerMount& m, std::size_t i) {
  const std::string where = "accelerometer[" + std::to_string(i) + "].";
  w.header("accelerometer", true);
  w.key(where + "name", "name", toml_quoted(m.name));
  w.key(where + "position", "position", toml_quoted(m.position));
  w.key(where + "axle", "axle", toml_quoted(m.axle));
  w.key(where + "on_axle", "on_axle", m.on_axle ? "true" : "false");
  w.numbers(where, vf::kAccelerometer, m);
}

}  // namespace

std::string format_vehicle(const Vehicle& v, const VehicleNotes& notes, std::string_view table) {
  Writer w(notes, table);
  w.header("");
  w.key("name", "name", toml_quoted(v.name));
  if (!v.description.empty()) w.key("description", "description", toml_quoted(v.description));
  if (!v.vin.empty()) w.key("vin", "vin", toml_quoted(v.vin));
  w.header("body");
  w.numbers("body.", vf::kBody, v);
  for (const auto& n : vf::kBodyOptional) {
    if (v.*n.member == 0) continue;
    std::string field = "body.";
    field.append(n.key);
    w.key(field, n.key, number(v.*n.member));
  }
  w.header("engine");
  w.numbers("engine.", vf::kEngine, v.engine);
  w.list("engine.", "full_load_rpm", v.engine.full_load_rpm);
  w.list("engine.", "full_load_fraction", v.engine.full_load_fraction);
  w.header("driveline");
  w.list("driveline.", "gear_ratios", v.driveline.gear_ratios);
  w.numbers("driveline.", vf::kDriveline, v.driveline);
  w.key("driveline.shift_time_s", "shift_time_s", number(v.driveline.shift_time.count()));
  w.header("fuel");
  w.numbers("fuel.", vf::kFuel, v.fuel);
  w.header("accessories");
  w.numbers("accessories.", vf::kAccessories, v.accessories);
  for (std::size_t i = 0; i < v.axles.size(); ++i) write_axle(w, v.axles[i], i);
  for (std::size_t i = 0; i < v.accelerometers.size(); ++i) write_accelerometer(w, v.accelerometers[i], i);
  return w.text();
}

}  // namespace roadload
