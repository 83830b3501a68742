#include "drive_record.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "roadload/content_hash.hpp"
#include "roadload/fleet/collect.hpp"
#include "roadload/results/results_dir.hpp"

namespace roadload::fleet {
namespace {

[[noreturn]] void fail(const std::string& file, long line, const std::string& field, const std::string& why) {
  throw ResultsError(ParseError{file, line, field, why});
}

// Provenance's text fields; `required` ones missing mean results no collect can place.
struct Provenance {
  const results::JsonValue* object = nullptr;
  std::string file;
  std::string text(const char* key, bool required = false) const {
    const results::JsonValue* v = object->find(key);
    if (v != nullptr && v->kind() == results::JsonValue::Kind::string) return v->string();
    if (required) fail(file, object->line(), std::string("provenance.") + key, "missing: analyse the drive again with this roadload");
    return {};
  }
};

db::Value number_or_null(const results::JsonValue& trip, const char* path) {
  const auto v = trip.number_at(path);
  return v && std::isfinite(*v) ? db::Value(*v) : db::Value();
}

db::Value cell(const results::NumberTable& t, std::size_t row, const char* column) {
  const auto c = t.column(column);
  if (!c) return {};
  const double v = t.at(row, *c);
  return std::isfinite(v) ? db::Value(v) : db::Value();
}

std::string cell_text(const results::NumberTable& t, std::size_t row, const char* column) {
  const auto c = t.column(column);
  return c ? t.text(row, *c) : std::string();
}

std::string canonical(const db::Value& v) {
  if (const auto* d = std::get_if<double>(&v)) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", *d);
    return b;
  }
  return db::text(v);
}

void read_sections(DriveRecord& d, const results::NumberTable& cells) {
  for (const char* required : {"cell", "crr", "crr_sigma", "surface", "start_lat_deg", "end_lon_deg"}) {
    if (!cells.column(required)) fail(cells.path(), 1, required, "no such column: analyse the drive again with this roadload");
  }
  for (std::size_t r = 0; r < cells.rows(); ++r) {
    SectionRecord s;
    s.cell = cell_text(cells, r, "cell");
    s.key = d.route_hash + ":" + s.cell;
    s.surface = cell_text(cells, r, "surface");
    s.start_m = db::number(cell(cells, r, "start_m")).value_or(NAN);
    s.end_m = db::number(cell(cells, r, "end_m")).value_or(NAN);
    const auto at = [&](const char* c) { return db::number(cell(cells, r, c)); };
    if (at("start_lat_deg") && at("start_lon_deg") && at("end_lat_deg") && at("end_lon_deg")) {
      s.start_lat = *at("start_lat_deg"), s.start_lon = *at("start_lon_deg");
      s.end_lat = *at("end_lat_deg"), s.end_lon = *at("end_lon_deg");
      s.placed = true;
      s.direction = direction_of(s.start_lat, s.start_lon, s.end_lat, s.end_lon);
    }
    d.sections.push_back(s);
    db::Row row;
    for (std::size_t c = 0; c < kResultColumnCount; ++c) {
      const std::string name = kResultColumns[c];
      row.push_back(name == "reason" ? db::Value(cell_text(cells, r, "reason")) : cell(cells, r, kResultColumns[c]));
    }
    d.results.push_back(std::move(row));
  }
}

}  // namespace

const char* const kResultColumns[] = {"samples",        "crr",          "crr_lo",    "crr_hi",      "crr_sigma",
                                      "identified",     "speed_mps",    "rolling_l", "dynamic_l",   "dynamic_l_per_100km",
                                      "damper_power_w", "tire_power_w", "crr_tire",  "crr_tire_lo", "crr_tire_hi",
                                      "reason"};
const std::size_t kResultColumnCount = std::size(kResultColumns);

std::string direction_of(double start_lat, double start_lon, double end_lat, double end_lon) {
  const double north = end_lat - start_lat, east = (end_lon - start_lon) * std::cos(start_lat * std::numbers::pi / 180);
  const double bearing = std::fmod(std::atan2(east, north) * 180 / std::numbers::pi + 360, 360);
  static const char* const names[] = {"NB", "EB", "SB", "WB"};
  return names[static_cast<int>(std::fmod(bearing + 45, 360) / 90)];
}

DriveRecord read_drive(const std::string& dir) {
  auto read = results::read_results_dir(dir);
  if (!read) throw ResultsError(read.error());
  const results::ResultsDir& r = read.value();
  DriveRecord d;
  d.dir = dir;
  const std::string trip_file = dir + "/trip.json";
  const results::JsonValue* prov = r.trip.find("provenance");
  if (prov == nullptr) fail(trip_file, r.trip.line(), "provenance", "missing: analyse the drive again with this roadload");
  const Provenance p{prov, trip_file};
  d.recording_id = p.text("recording_id");
  d.vin = p.text("vin");
  d.vehicle_name = p.text("vehicle", true);
  d.vehicle_hash = p.text("vehicle_hash", true);
  d.vehicle_source = p.text("vehicle_source");
  d.vehicle_key = d.vin.empty() ? d.vehicle_hash : "vin:" + d.vin;
  d.route_hash = p.text("route_hash", true);
  d.route_name = p.text("route_name");
  d.route = p.text("route");
  d.start_utc = p.text("drive_start_utc");
  d.end_utc = p.text("drive_end_utc");
  d.program = p.text("program");
  d.engine_losses = p.text("engine_losses");
  d.cda_prior = p.text("cda");
  d.torque_scale = p.text("torque_scale");
  const results::JsonValue* identified = r.trip.find("crr_identified");
  d.crr = number_or_null(r.trip, "crr");
  d.crr_sigma = number_or_null(r.trip, "crr_sigma");
  d.crr_identified = identified ? db::Value(std::int64_t{identified->boolean() ? 1 : 0}) : db::Value();
  d.mass_kg = number_or_null(r.trip, "mass_kg");
  d.cda_m2 = number_or_null(r.trip, "cda_m2");
  d.distance_m = number_or_null(r.trip, "fuel.distance_m");
  d.fuel_l = number_or_null(r.trip, "fuel.measured_l");
  read_sections(d, r.cells);
  // The results' identity: everything stored of them, so an unchanged drive is recognised
  // whatever folder it is read from.
  std::string all = d.vehicle_key + d.vehicle_hash + d.route_hash + d.start_utc + d.end_utc + d.program + d.engine_losses +
                    d.cda_prior + d.torque_scale;
  for (const db::Value* v : {&d.crr, &d.crr_sigma, &d.crr_identified, &d.mass_kg, &d.cda_m2, &d.distance_m, &d.fuel_l})
    all += "," + canonical(*v);
  for (std::size_t i = 0; i < d.results.size(); ++i) {
    all += "\n" + d.sections[i].key;
    for (const db::Value& v : d.results[i]) all += "," + canonical(v);
  }
  d.results_hash = content_hash(all);
  d.drive_key = d.recording_id.empty() ? "results:" + d.results_hash : d.recording_id;
  return d;
}

}  // namespace roadload::fleet
