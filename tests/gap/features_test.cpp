// The diagnosis reduces a recording read from disk and a simulation streamed from memory with one
// extractor: a drive must give the same features either way, or the residual would blame the
// model for the recording format.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include <unistd.h>

#include "roadload/definitions.hpp"
#include "roadload/gap/engine.hpp"
#include "roadload/gap/resimulate.hpp"
#include "roadload/sim/recording_sink.hpp"
#include "roadload/sim/simulation.hpp"

namespace roadload::gap {
namespace {

class GapFeatures : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(load_dbc_file(db_, ROADLOAD_CONFIG_DIR "/j1939-core.dbc"));
    auto s = sim::load_scenario("mnroad-mainline-30mph", ROADLOAD_CONFIG_DIR);
    ASSERT_TRUE(s) << s.error().to_string();
    scenario_ = s.value();
    scenario_.duration = Seconds{75.0};
    scenario_.accel_rate_hz = 400;
    dir_ = std::filesystem::temp_directory_path() / "gap-features";
    dir_ += std::to_string(::getpid());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The scenario's drive written to dir_ as a recording, its metadata changed by `edit` first.
  template <typename Edit>
  void write_recording(Edit&& edit) {
    sim::Simulation simulation(scenario_, 5, db_);
    recording::Metadata meta = simulation.metadata();
    edit(meta);
    auto writer = recording::RecordingWriter::create(dir_.string(), meta);
    ASSERT_TRUE(writer) << writer.error().to_string();
    sim::RecordingSink sink(writer.value());
    simulation.run(sink, nullptr);
    ASSERT_FALSE(writer.value().close());
  }

  j1939::Database db_;
  sim::Scenario scenario_;
  std::filesystem::path dir_;
};

TEST_F(GapFeatures, ARecordingAndItsSimulationInMemoryGiveTheSameFeatures) {
  const RunLayout layout = layout_for(scenario_.route);
  const RecordedRun memory = simulate_run(scenario_, 5, db_, layout);
  write_recording([](recording::Metadata&) {});
  const auto disk = read_run(dir_.string(), db_, layout, scenario_.vehicle);
  ASSERT_TRUE(disk) << disk.error().to_string();
  const auto& a = memory.features.features;
  const auto& b = disk.value().features.features;
  ASSERT_EQ(a.size(), b.size());
  std::size_t seen = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].channel, b[i].channel);
    ASSERT_EQ(a[i].where, b[i].where);
    ASSERT_EQ(std::isfinite(a[i].value), std::isfinite(b[i].value)) << a[i].channel << " " << a[i].where;
    if (!std::isfinite(a[i].value)) continue;
    ++seen;
    // The recording's text rounds accelerations to 10 um/s^2 and heights to a millimetre.
    EXPECT_NEAR(a[i].value, b[i].value, 1e-3 * std::max(1.0, std::abs(a[i].value))) << a[i].channel << " " << a[i].where;
  }
  // 75 s at 30 mph reach three cells: torque, fuel, speed, height in each, and the spectra.
  EXPECT_GT(seen, 30u);
  const RunConditions& c = disk.value().features.conditions;
  EXPECT_NEAR(c.mean_speed_mps, scenario_.speed_mps, 0.1);  // cruise control on the first grades
  EXPECT_NEAR(c.air_temp_c, scenario_.weather.air_temp_c, 0.5);
  EXPECT_FALSE(c.wind_trace.empty());
  EXPECT_TRUE(c.have_fix);
}

// A logger names its sensors as its installer did; the diagnosis matches them to the model's by
// where they are mounted.
TEST_F(GapFeatures, SensorsMeetTheModelsByMountingPositionWhateverTheirNames) {
  const RunLayout layout = layout_for(scenario_.route);
  scenario_.duration = Seconds{20.0};
  const RecordedRun memory = simulate_run(scenario_, 5, db_, layout);
  write_recording([](recording::Metadata& meta) {
    for (std::size_t i = 0; i < meta.sensors.size(); ++i) meta.sensors[i].name = "logger-ch" + std::to_string(i);
  });
  const auto disk = read_run(dir_.string(), db_, layout, scenario_.vehicle);
  ASSERT_TRUE(disk) << disk.error().to_string();
  std::set<std::string> a, b;
  for (const Feature& f : memory.features.features) a.insert(f.channel);
  for (const Feature& f : disk.value().features.features) b.insert(f.channel);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(a.contains("psd_db:tractor-front-axle-left"));
}

TEST(GapUnmatched, ChannelsOnOneSideOnlyAreNamedWithTheSideThatHasThem) {
  RealRun run;
  run.label = "drive";
  for (const char* c : {"torque_nm", "psd_db:tractor-front-axle-left", "psd_db:trailer-axle9-left"}) {
    run.recorded.features.features.push_back({c, "cell 1", 0, 1.0});
  }
  ModelLibrary lib;
  lib.labels = {"drive"};
  for (const char* c : {"torque_nm", "psd_db:tractor-front-axle-left", "psd_db:tractor-drive1-axle-left"}) {
    lib.keys.push_back({"drive", c, "cell 1", 0});
  }
  const std::vector<UnmatchedChannel> u = unmatched_channels({run}, lib);
  ASSERT_EQ(u.size(), 2u);
  EXPECT_EQ(u[0].channel, "psd_db:trailer-axle9-left");
  EXPECT_TRUE(u[0].recording_only);
  EXPECT_EQ(u[1].channel, "psd_db:tractor-drive1-axle-left");
  EXPECT_FALSE(u[1].recording_only);
}

TEST_F(GapFeatures, TheReSimulationTakesSpeedWeatherMassAndWarmUpFromTheRecording) {
  RunConditions c;
  c.mean_speed_mps = 20.0;
  c.duration_s = 100.0;
  c.weather_samples = 10;
  c.air_temp_c = 25.0;
  c.pressure_pa = 97000.0;
  c.wind_trace = {{0.0, 1.0, 2.0}, {50.0, 1.5, 2.5}};
  recording::Metadata meta;
  meta.vehicle["mass_kg"] = 36152.0 * 1.1;
  const sim::Scenario s = resimulation(scenario_, c, meta);
  EXPECT_DOUBLE_EQ(s.speed_mps, 20.0);
  EXPECT_DOUBLE_EQ(s.duration->count(), 75.0);  // the model's shorter run is kept
  EXPECT_DOUBLE_EQ(s.weather.air_temp_c, 25.0);
  EXPECT_DOUBLE_EQ(s.weather.pressure_pa, 97000.0);
  EXPECT_EQ(s.weather.wind_trace.size(), 2u);
  EXPECT_NEAR(s.load_scale, 1.1, 1e-3);
  EXPECT_EQ(s.driven_before, sim::kReportWarmUp);  // not stated: the model's
  sim::Scenario yard = scenario_;
  yard.driven_before = Seconds{300.0};
  EXPECT_EQ(resimulation(yard, c, meta).driven_before.count(), 300.0);
  meta.vehicle["driven_before_s"] = 600.0;
  EXPECT_EQ(resimulation(yard, c, meta).driven_before.count(), 600.0);
  // A mean speed within 0.3 m/s of the model's is the model's set speed driven.
  c.mean_speed_mps = scenario_.speed_mps + 0.2;
  EXPECT_DOUBLE_EQ(resimulation(scenario_, c, meta).speed_mps, scenario_.speed_mps);
}

}  // namespace
}  // namespace roadload::gap
