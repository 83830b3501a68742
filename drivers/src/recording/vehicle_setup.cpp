#include "roadload/recording/vehicle_setup.hpp"

namespace roadload::recording {

AnalyzerConfig config_from_vehicle(const std::map<std::string, double>& vehicle, std::optional<double> mass) {
  AnalyzerConfig cfg;
  if (mass) {
    cfg.filter.truck.mass_kg = *mass;
  } else if (auto it = vehicle.find("mass_kg"); it != vehicle.end()) {
    cfg.filter.truck.mass_kg = it->second;
  }
  double moment = 0, load = 0;
  std::vector<AxleLoad> axles;
  for (const AxleDefaults& axle : kMnroadAxles) {
    const auto l = vehicle.find(std::string(axle.name) + "_load_kg");
    const auto x = vehicle.find(std::string(axle.name) + "_position_m");
    if (l != vehicle.end() && x != vehicle.end()) {
      moment += l->second * x->second;
      load += l->second;
      axles.push_back({x->second, l->second});
    }
  }
  if (load > 0) {
    cfg.cg_behind_front_m = moment / load;
    cfg.axles = axles;
  }
  if (auto it = vehicle.find("gnss_antenna_behind_front_axle_m"); it != vehicle.end()) cfg.antenna_behind_front_m = it->second;
  return cfg;
}

LayoutResult axle_layout(const Metadata& meta, const std::string& source) {
  std::vector<SensorPlacement> placements;
  for (const auto& s : meta.sensors) placements.push_back({s.id, s.kind, s.position});
  LayoutOptions lenient;
  lenient.skip_axles_without_sensors = true;
  auto layout = build_axle_layout(placements, meta.vehicle, source, lenient);
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
