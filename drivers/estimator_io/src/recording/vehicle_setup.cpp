#include "roadload/recording/vehicle_setup.hpp"

namespace roadload::recording {

AnalyzerConfig analyzer_config_for(const Vehicle& vehicle, const Metadata& meta, std::optional<double> mass) {
  AnalyzerConfig cfg = analyzer_config(vehicle);
  if (mass) {
    cfg.filter.truck.mass_kg = *mass;
  } else if (auto it = meta.vehicle.find("mass_kg"); it != meta.vehicle.end()) {
    cfg.filter.truck.mass_kg = it->second;
  }
  return cfg;
}

LayoutResult axle_layout(const Metadata& meta, const Vehicle& vehicle, const std::string& source) {
  std::vector<SensorPlacement> placements;
  for (const auto& s : meta.sensors) placements.push_back({s.id, s.kind, s.position});
  LayoutOptions lenient;
  lenient.skip_axles_without_sensors = true;
  auto layout = build_axle_layout(placements, vehicle, source, lenient);
  LayoutResult r;
  if (!layout) {
    r.why_not = layout.error().to_string();
    return r;
  }
  r.skipped = layout.value().skipped;
  r.layout = std::move(layout.value());
  return r;
}

std::vector<VibrationSensor> accelerometers(const Metadata& meta) {
  std::vector<VibrationSensor> out;
  for (const auto& s : meta.sensors) {
    if (s.kind == "accelerometer" && s.id >= 0 && s.id < 256) out.push_back({static_cast<std::uint8_t>(s.id), s.name, s.rate_hz});
  }
  return out;
}

}  // namespace roadload::recording
