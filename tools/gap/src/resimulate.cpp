#include "roadload/gap/resimulate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <variant>

#include "roadload/merge.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/sim/simulation.hpp"
#include "roadload/sim/truck.hpp"

namespace roadload::gap {
namespace {

// Samples reach a sink in physics order, each stamped later by its sensor's latency; a recording
// holds each stream as it came and its reader merges them by oldest stamp. Held a second per stream
// and merged the same way, the extractor sees a simulation exactly as it reads its recording back.
class ExtractorSink final : public sim::SampleSink {
 public:
  explicit ExtractorSink(FeatureExtractor& x) : x_(x) {}
  void frame(const CanFrame& f) override { hold(frames_, f); }
  void accel(const AccelSample& s) override { hold(accels_, s); }
  void gnss(const GnssFix& s) override { hold(fixes_, s); }
  void weather(const WeatherSample& s) override { hold(weather_, s); }
  void flush() { release(CaptureTime::max()); }

 private:
  static constexpr Nanoseconds kHold{1'000'000'000};
  static constexpr std::size_t kStreams = 4;

  template <typename T>
  void hold(std::deque<T>& stream, const T& sample) {
    stream.push_back(sample);
    latest_ = std::max(latest_, sample.t);
    release(latest_ - kHold);
  }
  // One typed queue per stream, in the order of recording::Record's alternatives: a simulation
  // hands over millions of samples, and a variant per sample cost a tenth of a diagnosis.
  template <typename F>
  decltype(auto) on_stream(std::size_t k, F&& f) {
    switch (k) {
      case 0: return f(frames_);
      case 1: return f(accels_);
      case 2: return f(fixes_);
      default: return f(weather_);
    }
  }
  void release(CaptureTime before) {
    while (const auto i = oldest_head(
               kStreams, [&](std::size_t k) { return on_stream(k, [](const auto& q) { return !q.empty(); }); },
               [&](std::size_t k) { return on_stream(k, [](const auto& q) { return q.front().t; }); })) {
      const bool due = on_stream(*i, [&](auto& q) {
        if (q.front().t >= before) return false;
        x_.push(q.front());
        q.pop_front();
        return true;
      });
      if (!due) return;
    }
  }

  FeatureExtractor& x_;
  std::deque<CanFrame> frames_;
  std::deque<AccelSample> accels_;
  std::deque<GnssFix> fixes_;
  std::deque<WeatherSample> weather_;
  CaptureTime latest_ = CaptureTime::min();
};

}  // namespace

RunLayout layout_for(const sim::RouteDef& route) {
  auto geometry = RouteGeometry::build(route.points);
  RunLayout layout{*geometry, {}};
  for (const auto& c : route.cells) layout.bins.push_back({c.id, c.start_m, c.end_m, c.surface == "concrete"});
  if (layout.bins.empty()) {
    const double length = layout.geometry.length_m();
    for (double s = 0; s < length; s += 250.0) {
      layout.bins.push_back({std::to_string(static_cast<long>(s)) + " m", s, std::min(s + 250.0, length), false});
    }
  }
  return layout;
}

Parsed<RecordedRun> read_run(const std::string& path, const j1939::Database& db, const RunLayout& layout, const Vehicle& base) {
  auto reader = recording::RecordingReader::open(path);
  if (!reader) return reader.error();
  if (!reader.value().has_metadata())
    return ParseError{path, 0, recording::kMetaFile, "missing: the re-simulation needs the vehicle"};
  RecordedRun run{reader.value().metadata(), {}, {}};
  FeatureExtractor x(db, layout, run.meta, base);
  // Records per stream, in the order of recording::Record's alternatives.
  std::array<std::uint64_t, std::variant_size_v<recording::Record>> records{};
  while (const recording::Record* r = reader.value().next()) {
    std::visit([&](const auto& s) { x.push(s); }, *r);
    ++records[r->index()];
  }
  const auto& errors = reader.value().errors();
  const std::array<const char*, 4> files{recording::kCanFile, recording::kAccelFile, recording::kGnssFile, recording::kWeatherFile};
  for (std::size_t k = 0; k < files.size() && k < records.size(); ++k) {
    const std::uint64_t bad = errors.count_in(files[k]), lines = records[k] + bad;
    if (bad == 0 || static_cast<double>(bad) <= 0.01 * static_cast<double>(lines)) continue;
    ParseError first = errors.kept().front();
    first.message += " (" + std::to_string(bad) + " malformed lines of " + std::to_string(lines) + " in " + files[k] +
                     ": more than 1 %, too damaged to diagnose)";
    return first;
  }
  run.malformed = errors;
  run.features = x.finish();
  if (run.features.conditions.speed_samples == 0) return ParseError{path, 0, "CCVS1", "no wheel speed: nothing to re-simulate"};
  return run;
}

Seconds driven_before(const recording::Metadata& meta, const sim::Scenario& model) {
  // The metadata reader refuses a value outside 0-86400 s.
  const auto it = meta.vehicle.find("driven_before_s");
  return it != meta.vehicle.end() ? Seconds{it->second} : model.driven_before;
}

sim::Scenario resimulation(const sim::Scenario& model, const RunConditions& c, const recording::Metadata& meta) {
  sim::Scenario s = model;
  // A drive near the model's set speed was driven at it: the measured mean carries the cruise
  // loop's own error, which the re-simulation reproduces. A coast-down's speed is the model's
  // entry speed; its mean is what the run is about.
  if (!model.coast && c.mean_speed_mps > 0.5 && c.mean_speed_mps <= 40.0 && std::abs(c.mean_speed_mps - model.speed_mps) > 0.3) {
    s.speed_mps = c.mean_speed_mps;
  }
  if (c.duration_s > 0) s.duration = std::min(model.duration.value_or(Seconds{1e9}), Seconds{c.duration_s + 1.0});
  if (c.weather_samples > 0) {
    s.weather.air_temp_c = c.air_temp_c;
    s.weather.temp_drift_c_per_h = c.temp_drift_c_per_h;
    s.weather.pressure_pa = c.pressure_pa;
    s.weather.wind_speed_mps = c.wind_speed_mps;
    s.weather.wind_from_deg = c.wind_from_deg;
    s.weather.wind_trace = c.wind_trace;
  }
  if (auto it = meta.vehicle.find("mass_kg"); it != meta.vehicle.end() && it->second > 0) {
    s.load_scale = std::clamp(it->second / model.vehicle.mass_kg(), 0.5, 1.5);
  }
  s.driven_before = driven_before(meta, model);
  return s;
}

RecordedRun simulate_run(const sim::Scenario& scenario, std::uint64_t seed, const j1939::Database& db, const RunLayout& layout) {
  sim::Simulation simulation(scenario, seed, db);
  RecordedRun run{simulation.metadata(), {}, {}};
  FeatureExtractor x(db, layout, run.meta, scenario.vehicle);
  ExtractorSink sink(x);
  simulation.run(sink, nullptr);
  sink.flush();
  run.features = x.finish();
  return run;
}

}  // namespace roadload::gap
