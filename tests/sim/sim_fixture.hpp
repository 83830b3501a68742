#pragma once
// Shared by the simulator's tests: built-in scenarios from the source tree and a sink that keeps
// everything in memory.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"

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

inline Scenario builtin(const std::string& name) {
  auto s = load_scenario(name, ROADLOAD_CONFIG_DIR);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
  return s.value();
}

inline j1939::Database core_database() {
  j1939::Database db;
  const auto err = load_dbc_file(db, std::string(ROADLOAD_CONFIG_DIR) + "/j1939-core.dbc");
  EXPECT_FALSE(err.has_value());
  return db;
}

}  // namespace roadload::sim::test
