#include "network_map.hpp"
#include "network_text.hpp"
#include "roadload/fleet/network.hpp"
#include "roadload/results/json.hpp"

namespace roadload::fleet {
namespace {

using results::json_quote;

// A CSV field: quoted when it holds a separator, a quote or a line break.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string sections_csv(const NetworkView& v) {
  std::string out =
      "route,cell,direction,surface,start_m,end_m,drives,trucks,cells,crr,crr_lo,crr_hi,crr_sigma,speed_mps,"
      "dynamic_l_per_100km,dynamic_l_per_100km_se,rolling_l_per_pass,dynamic_l_per_pass,rolling_l_per_year,dynamic_l_per_year,"
      "cost_per_year,start_lat_deg,start_lon_deg,end_lat_deg,end_lon_deg,route_hash\n";
  for (const NetworkSection& s : v.sections) {
    const double price = v.options.fuel_price_per_l;
    const std::string cost = price > 0 ? csv_number((s.rolling_l_per_year + s.dynamic_l_per_year) * price, 0) : "";
    out += field(s.route) + "," + field(s.cell) + "," + s.direction + "," + field(s.surface) + "," + csv_number(s.start_m, 1) + "," +
           csv_number(s.end_m, 1) + "," + std::to_string(s.drives) + "," + std::to_string(s.trucks) + "," + std::to_string(s.cells) +
           "," + csv_number(s.crr.crr, 6) + "," + csv_number(s.crr.crr_lo, 6) + "," + csv_number(s.crr.crr_hi, 6) + "," +
           csv_number(s.crr.crr_sigma, 6) + "," + csv_number(s.speed_mps, 2) + "," + csv_number(s.dynamic_l_per_100km, 4) + "," +
           csv_number(s.dynamic_l_per_100km_se, 4) + "," + csv_number(s.rolling_l_per_pass, 5) + "," +
           csv_number(s.dynamic_l_per_pass, 6) + "," + csv_number(s.rolling_l_per_year, 0) + "," +
           csv_number(s.dynamic_l_per_year, 0) + "," + cost + "," + (s.placed ? csv_number(s.start_lat, 7) : "") + "," +
           (s.placed ? csv_number(s.start_lon, 7) : "") + "," + (s.placed ? csv_number(s.end_lat, 7) : "") + "," +
           (s.placed ? csv_number(s.end_lon, 7) : "") + "," + s.route_hash + "\n";
  }
  return out;
}

std::string bands_csv(const NetworkView& v) {
  std::string out = "route,cell,direction,surface,band_lo_kmh,band_hi_kmh,drives,trucks,crr,crr_lo,crr_hi,crr_sigma\n";
  for (const NetworkBand& b : v.bands) {
    const NetworkSection& s = v.sections[b.section];
    out += field(s.route) + "," + field(s.cell) + "," + s.direction + "," + field(s.surface) + "," + csv_number(b.lo_mps * 3.6, 0) +
           "," + csv_number(b.hi_mps * 3.6, 0) + "," + std::to_string(b.drives) + "," + std::to_string(b.trucks) + "," +
           csv_number(b.crr.crr, 6) + "," + csv_number(b.crr.crr_lo, 6) + "," + csv_number(b.crr.crr_hi, 6) + "," +
           csv_number(b.crr.crr_sigma, 6) + "\n";
  }
  return out;
}

std::string trucks_csv(const NetworkView& v) {
  std::string out = "vehicle_key,vin,name,drives,tire_offset,tire_offset_sd,drag_at_reference_speed\n";
  for (const NetworkTruck& t : v.trucks) {
    out += field(t.key) + "," + field(t.vin) + "," + field(t.name) + "," + std::to_string(t.drives) + "," +
           csv_number(t.effect.offset, 7) + "," + csv_number(t.effect.offset_sd, 7) + "," + csv_number(t.effect.drag, 7) + "\n";
  }
  return out;
}

std::string geojson(const NetworkView& v) {
  std::string out = "{\"type\": \"FeatureCollection\", \"features\": [";
  bool first = true;
  for (const NetworkSection& s : v.sections) {
    if (!s.placed) continue;
    out += std::string(first ? "" : ",") +
           "\n  {\"type\": \"Feature\", \"geometry\": {\"type\": \"LineString\", \"coordinates\": [[" + csv_number(s.start_lon, 7) +
           ", " + csv_number(s.start_lat, 7) + "], [" + csv_number(s.end_lon, 7) + ", " + csv_number(s.end_lat, 7) +
           "]]}, \"properties\": {\"route\": " + json_quote(s.route) + ", \"cell\": " + json_quote(s.cell) +
           ", \"direction\": " + json_quote(s.direction) + ", \"surface\": " + json_quote(s.surface) +
           ", \"crr\": " + json_number(s.crr.crr, 6) + ", \"crr_lo\": " + json_number(s.crr.crr_lo, 6) +
           ", \"crr_hi\": " + json_number(s.crr.crr_hi, 6) + ", \"drives\": " + std::to_string(s.drives) +
           ", \"trucks\": " + std::to_string(s.trucks) + ", \"dynamic_l_per_100km\": " + json_number(s.dynamic_l_per_100km, 4) + "}}";
    first = false;
  }
  return out + "\n]}\n";
}

std::string component(const char* name, const network::VarianceComponent& c) {
  return std::string("    ") + json_quote(name) + ": {\"sd\": " + json_number(c.sd, 7) + ", \"sd_lo\": " + json_number(c.sd_lo, 7) +
         ", \"sd_hi\": " + json_number(c.sd_hi, 7) + "}";
}

std::string summary_json(const NetworkView& v) {
  std::string excluded;
  for (const auto& [why, n] : v.excluded) excluded += (excluded.empty() ? "" : ", ") + json_quote(why) + ": " + std::to_string(n);
  return "{\n  \"drives\": " + std::to_string(v.drives) + ",\n  \"trucks\": " + std::to_string(v.trucks.size()) +
         ",\n  \"sections\": " + std::to_string(v.sections.size()) + ",\n  \"cells_used\": " + std::to_string(v.cells_used) +
         ",\n  \"cells_excluded\": {" + excluded + "},\n  \"fitted\": " + (v.fit.fitted ? "true" : "false") +
         ",\n  \"crr\": " + (v.static_crr ? "\"crr_tire\"" : "\"crr\"") +
         ",\n  \"reference_speed_mps\": " + json_number(v.fit.reference_speed_mps, 3) +
         ",\n  \"fleet_speed_slope\": " + json_number(v.fit.fleet_speed_slope, 7) + ",\n  \"spread\": {\n" +
         component("cell", v.fit.cell) + ",\n" + component("drive", v.fit.drive) + ",\n" + component("truck", v.fit.truck) + ",\n" +
         component("truck_drag", v.fit.truck_drag) + "\n  },\n  \"trucks_per_day\": " + json_number(v.options.trucks_per_day, 1) +
         ",\n  \"fuel_price_per_l\": " + json_number(v.options.fuel_price_per_l, 3) + "\n}\n";
}

}  // namespace

std::map<std::string, std::string> network_files(const NetworkView& view) {
  return {{"network.csv", sections_csv(view)}, {"network-bands.csv", bands_csv(view)}, {"trucks.csv", trucks_csv(view)},
          {"network.geojson", geojson(view)},  {"network.json", summary_json(view)},   {"network.html", network_map(view)}};
}

}  // namespace roadload::fleet
