#include "roadload/results/provenance.hpp"

#include <cstdio>

#include "roadload/results/json.hpp"

namespace roadload::results {

std::string cda_text(double cda_m2, double sigma_m2, const std::string& source) {
  char text[96];
  std::snprintf(text, sizeof text, "%.3f m2 +- %.3f (", cda_m2, sigma_m2);
  return text + source + ")";
}

std::string engine_losses_text(const std::string& table) { return table.empty() ? "EEC3's nominal friction percent" : table; }

std::string provenance_json(const Provenance& p) {
  const auto text = [](const std::string& v) { return v.empty() ? std::string("null") : json_quote(v); };
  std::string j = "  \"provenance\": {\n    \"program\": " + text(p.program) + ",\n    \"recordings\": [";
  for (std::size_t i = 0; i < p.recordings.size(); ++i) j += (i ? ", " : "") + json_quote(p.recordings[i]);
  j += "],\n    \"recording_id\": " + text(p.recording_id) + ",\n    \"vehicle\": " + text(p.vehicle) +
       ",\n    \"vin\": " + text(p.vin) + ",\n    \"vehicle_source\": " + text(p.vehicle_source) +
       ",\n    \"vehicle_hash\": " + text(p.vehicle_hash) + ",\n    \"route\": " + text(p.route) +
       ",\n    \"route_name\": " + text(p.route_name) + ",\n    \"route_hash\": " + text(p.route_hash) +
       ",\n    \"drive_start_utc\": " + text(p.drive_start_utc) + ",\n    \"drive_end_utc\": " + text(p.drive_end_utc) +
       ",\n    \"engine_losses\": " + text(p.engine_losses) + ",\n    \"cda\": " + text(p.cda) +
       ",\n    \"torque_scale\": " + text(p.torque_scale) + "\n  }";
  return j;
}

}  // namespace roadload::results
