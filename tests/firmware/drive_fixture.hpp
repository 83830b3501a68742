#pragma once
// A simulated drive in memory and a daemon wired to replay it from memory sources: the same
// threads, rings, recorder and live estimator as roadloadd, without devices.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <variant>

#include <gtest/gtest.h>

#include "daemon_setup.hpp"
#include "memory_source.hpp"
#include "roadload/firmware/daemon.hpp"
#include "roadload/recording/reader.hpp"
#include "sim_fixture.hpp"

namespace roadload::firmware::test {

struct SimulatedDrive {
  // The scenario's eight accelerometers by default; tests of the merge's timing take fewer, so
  // that the estimator keeps up with the pace under the sanitizers on a loaded machine.
  explicit SimulatedDrive(double duration_s, std::size_t accelerometers = 8) : db(sim::test::core_database()) {
    scenario = sim::test::builtin("mnroad-mainline-30mph");
    scenario.duration = Seconds{duration_s};
    scenario.accelerometers = accelerometers;
    sim::Simulation s(scenario, 7, db);
    meta = s.metadata();
    s.run(sink, nullptr);
  }
  j1939::Database db;
  sim::Scenario scenario;
  recording::Metadata meta;
  sim::test::MemorySink sink;
};

// The drive runs this many times faster than real time: fast for a test, slow enough that the
// writer and estimator keep up on a loaded CI machine without a ring filling.
inline constexpr double kPace = 5;

// Every stream of the drive gated at `gate_fraction` of its items (1: no gate); one accelerometer
// source per sensor, as the daemon has one per part.
inline Pace start_pace(const SimulatedDrive& d) { return {std::chrono::steady_clock::now(), d.sink.frames.front().t, kPace}; }

// The accelerometers as replays (their own threads, waiting for room) or, with kernel stamps, as
// devices (read in turn by one thread, dropping what a full ring refuses).
inline DaemonSources memory_sources(const SimulatedDrive& d, const Pace& pace, const std::atomic<bool>& gate, double gate_fraction,
                                    StampSource accel_stamps = StampSource::recording) {
  auto at = [&](std::size_t n) { return static_cast<std::size_t>(static_cast<double>(n) * gate_fraction); };
  DaemonSources s;
  s.can.push_back(std::make_unique<CanChannel>(
      std::make_unique<MemorySource<CanFrame>>(d.sink.frames, gate, at(d.sink.frames.size()), "can0", pace), SourceKind::can,
      "can0"));
  std::map<std::uint8_t, std::vector<AccelSample>> per_sensor;
  for (const AccelSample& a : d.sink.accels) per_sensor[a.sensor].push_back(a);
  for (auto& [id, samples] : per_sensor) {
    const std::size_t gate_at = at(samples.size());
    s.accel.push_back(std::make_unique<AccelChannel>(
        std::make_unique<MemorySource<AccelSample>>(std::move(samples), gate, gate_at, "accel", pace, accel_stamps),
        SourceKind::accelerometer, "accel" + std::to_string(id)));
  }
  s.gnss = std::make_unique<GnssChannel>(
      std::make_unique<MemorySource<GnssFix>>(d.sink.fixes, gate, at(d.sink.fixes.size()), "gnss", pace), SourceKind::gnss, "gnss");
  s.weather = std::make_unique<WeatherChannel>(
      std::make_unique<MemorySource<WeatherSample>>(d.sink.weather_samples, gate, at(d.sink.weather_samples.size()), "weather", pace),
      SourceKind::weather, "weather");
  return s;
}

// The merge waits the wall second a truck's daemon would for a starved thread, at the test's pace.
inline DaemonSetup daemon_setup(const SimulatedDrive& d, const std::string& data_dir) {
  DaemonSetup setup = simulated_daemon_setup(d.scenario, d.meta, d.db, data_dir, true);
  setup.max_merge_wait = std::chrono::duration_cast<Nanoseconds>(std::chrono::duration<double>(kPace));
  return setup;
}

inline void wait_for(Daemon& daemon) {
  for (int i = 0; i < 6000 && !daemon.replays_finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

// Accelerometer rows in the segments of the recording under `dir`; a segment that does not read
// fails the test.
inline std::size_t recorded_accel_rows(const std::string& dir) {
  std::size_t rows = 0;
  for (const auto& segment : std::filesystem::directory_iterator(dir)) {
    auto reader = recording::RecordingReader::open(segment.path().string(), recording::kAccelStream);
    if (!reader.ok()) {
      ADD_FAILURE() << reader.error().to_string();
      continue;
    }
    while (const recording::Record* rec = reader.value().next()) rows += std::holds_alternative<AccelSample>(*rec) ? 1 : 0;
  }
  return rows;
}

inline std::string temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

}  // namespace roadload::firmware::test
