// Simulation speed: an hour of driving with 8 tri-axial accelerometers at 1,200 Hz written to a
// recording, against the same drive with no sensors and no output (the plant alone). Prints
// figures; it does not pass or fail. Goal: the full run under 60 s on one core.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "roadload/definitions.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/sim/recording_sink.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"

namespace {

using Clock = std::chrono::steady_clock;

class NullSink final : public roadload::sim::SampleSink {
 public:
  void frame(const roadload::CanFrame&) override {}
  void accel(const roadload::AccelSample&) override {}
  void gnss(const roadload::GnssFix&) override {}
  void weather(const roadload::WeatherSample&) override {}
};

struct Timing {
  double wall_s;
  roadload::sim::RunSummary summary;
};

Timing run(const roadload::sim::Scenario& sc, const roadload::j1939::Database& db, const std::string* folder) {
  roadload::sim::Simulation sim(sc, 1, db);
  const auto t0 = Clock::now();
  roadload::sim::RunSummary sum;
  if (folder != nullptr) {
    auto w = roadload::recording::RecordingWriter::create(*folder, sim.metadata());
    if (!w) {
      std::fprintf(stderr, "bench: %s\n", w.error().to_string().c_str());
      std::exit(1);
    }
    roadload::sim::RecordingSink sink(w.value());
    sum = sim.run(sink, nullptr);
    if (auto e = w.value().close()) {
      std::fprintf(stderr, "bench: %s\n", e->to_string().c_str());
      std::exit(1);
    }
  } else {
    NullSink sink;
    sum = sim.run(sink, nullptr);
  }
  return {std::chrono::duration<double>(Clock::now() - t0).count(), sum};
}

}  // namespace

int main(int argc, char** argv) {
  const double duration_s = argc > 1 ? std::atof(argv[1]) : 3600.0;
  auto sc = roadload::sim::load_scenario("highway-1h", ROADLOAD_CONFIG_DIR);
  if (!sc) {
    std::fprintf(stderr, "bench: %s\n", sc.error().to_string().c_str());
    return 1;
  }
  sc.value().duration = roadload::Seconds{duration_s};
  roadload::j1939::Database db;
  if (auto e = roadload::load_dbc_file(db, std::string(ROADLOAD_CONFIG_DIR "/j1939-core.dbc"))) return 1;

  const std::string folder = (std::filesystem::temp_directory_path() / "roadload-bench-simulate").string();
  std::filesystem::remove_all(folder);
  const Timing full = run(sc.value(), db, &folder);
  std::uintmax_t bytes = 0;
  for (const auto& e : std::filesystem::directory_iterator(folder)) bytes += e.file_size();
  std::filesystem::remove_all(folder);

  auto bare = sc.value();
  bare.accelerometers = 0;
  const Timing plant = run(bare, db, nullptr);

  std::printf("simulate: %.0f s of driving (%.1f km), %zu accelerometers x 3 axes at %.0f Hz\n", full.summary.simulated_s,
              full.summary.distance_m / 1000, sc.value().accelerometers, sc.value().accel_rate_hz);
  std::printf("  full run, recording written : %7.2f s wall  %6.1fx real time  %" PRIu64 " accel samples, %" PRIu64
              " CAN frames, %.2f GB\n",
              full.wall_s, full.summary.simulated_s / full.wall_s, full.summary.accel_samples, full.summary.frames,
              static_cast<double>(bytes) / 1e9);
  std::printf("  reference: plant, no sensors: %7.2f s wall  %6.1fx real time  (full / reference %.2f)\n", plant.wall_s,
              plant.summary.simulated_s / plant.wall_s, full.wall_s / plant.wall_s);
  std::printf("  goal: one hour in under 60 s -> %s (%.1f s projected for 3600 s)\n",
              full.wall_s * 3600.0 / full.summary.simulated_s < 60.0 ? "met" : "NOT met",
              full.wall_s * 3600.0 / full.summary.simulated_s);
  return 0;
}
