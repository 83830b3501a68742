#pragma once
// A simulated drive kept in memory and handed to the estimator as a recording reader would hand it
// over: shared by the simulator's tests and the accuracy benchmark.
#include <stdexcept>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/pavement_groups.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/sim/simulation.hpp"
#include "vehicles.hpp"

namespace roadload::sim::test {

class MemorySink final : public SampleSink {
 public:
  void frame(const CanFrame& f) override { frames.push_back(f); }
  void accel(const AccelSample& s) override { accels.push_back(s); }
  void gnss(const GnssFix& s) override { fixes.push_back(s); }
  void weather(const WeatherSample& s) override { weather_samples.push_back(s); }

  std::vector<CanFrame> frames;
  std::vector<AccelSample> accels;
  std::vector<GnssFix> fixes;
  std::vector<WeatherSample> weather_samples;
};

// The accelerometers only, with a look at the plant once a physics step before that step's samples
// go on: estimators are fed as samples arrive and the truth is read where it stands.
class PlantStepSink : public SampleSink {
 public:
  explicit PlantStepSink(const Simulation& sim) : sim_(sim) {}
  void frame(const CanFrame&) override {}
  void gnss(const GnssFix&) override {}
  void weather(const WeatherSample&) override {}
  void accel(const AccelSample& s) final {
    const TruckState& st = sim_.plant().state();
    if (st.t_s != last_t_) {
      last_t_ = st.t_s;
      step(st);
    }
    sample(s);
  }

 protected:
  virtual void step(const TruckState& st) = 0;
  virtual void sample(const AccelSample& s) = 0;
  // The route cell under an axle `behind_m` behind the front axle; -1 off the cells.
  int cell_under(const TruckState& st, double behind_m) const {
    const Route& r = sim_.route();
    const Cell* c = r.cell_at(st.x_m - behind_m);
    return c == nullptr ? -1 : static_cast<int>(c - r.def().cells.data());
  }

  const Simulation& sim_;

 private:
  double last_t_ = -1;
};

// The cells of a scenario's route, as the estimator takes them.
inline std::vector<CellSpan> cell_spans(const Scenario& sc) {
  std::vector<CellSpan> cells;
  for (const Cell& c : sc.route.cells) cells.push_back({c.id, c.start_m, c.end_m, iri_from_gd_m_per_km(c.gd_n0_m3)});
  return cells;
}

// The analyzer's defaults with the route's roughness where its cells state none, as `roadload
// analyze` takes it from the route file.
inline AnalyzerConfig analyzer_config(const Scenario& sc) {
  AnalyzerConfig c = roadload::analyzer_config(sc.vehicle);
  c.roughness_iri_m_per_km = iri_from_gd_m_per_km(sc.route.default_gd_n0_m3);
  return c;
}

// CAN, GNSS, weather and, with `accels`, the accelerometers in capture-time order, then the smoother.
inline void analyze(DriveAnalyzer& analyzer, const MemorySink& sink, bool accels = false) {
  std::size_t f = 0, g = 0, w = 0, a = 0;
  while (f < sink.frames.size()) {
    const CaptureTime t = sink.frames[f].t;
    while (g < sink.fixes.size() && sink.fixes[g].t <= t) analyzer.push(sink.fixes[g++]);
    while (w < sink.weather_samples.size() && sink.weather_samples[w].t <= t) analyzer.push(sink.weather_samples[w++]);
    while (accels && a < sink.accels.size() && sink.accels[a].t <= t) analyzer.push(sink.accels[a++]);
    analyzer.push(sink.frames[f++]);
  }
  analyzer.finish();
}

// The truck's axles and accelerometers as a recording's metadata describes them (every axle with
// a load must have its sensors: the simulator mounts them all).
inline AxleLayout axle_layout(const recording::Metadata& m) {
  std::vector<SensorPlacement> p;
  for (const auto& s : m.sensors) p.push_back({s.id, s.kind, s.position});
  auto l = build_axle_layout(p, recording::vehicle_from_metadata(roadload::shipped::mnroad_vehicle(), m));
  if (!l) throw std::runtime_error(l.error().to_string());
  return l.value();
}

// The pavement groups of a scenario's cells.
inline PavementGroups pavement_groups(const Scenario& sc) {
  std::vector<PavementKey> keys;
  for (const Cell& c : sc.route.cells) keys.push_back({c.surface, c.joint_spacing_m});
  return group_pavements(keys);
}

}  // namespace roadload::sim::test
