// The test-days file of `roadload gap bench`: the shipped days load as documented, and a wrong
// field is refused with its file, line and name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "roadload/gap/bench.hpp"

namespace roadload::gap {
namespace {

TEST(GapBenchDays, ShippedDaysEachHoldACoastDownBetweenTwoCruiseRuns) {
  const auto days = load_bench_days(default_bench_days(ROADLOAD_CONFIG_DIR), ROADLOAD_CONFIG_DIR);
  ASSERT_TRUE(days) << days.error().to_string();
  ASSERT_EQ(days.value().size(), 4u);
  for (const BenchDay& d : days.value()) {
    SCOPED_TRACE(d.road);
    ASSERT_EQ(d.drives.size(), 3u);
    ASSERT_EQ(d.models.size(), 3u);
    EXPECT_FALSE(d.drives[0].coast);
    EXPECT_TRUE(d.drives[1].coast);
    EXPECT_TRUE(d.models[1].coast);
    EXPECT_FALSE(d.drives[2].coast);
    // The first cruise is slower than the last: two speeds, two gears.
    EXPECT_LT(d.drives[0].speed_mps + 2.0, d.drives[2].speed_mps);
    // The model keeps its scenario's weather; the drive has the day's.
    EXPECT_NE(d.drives[0].weather.air_temp_c, d.drives[2].weather.air_temp_c);
    // The morning run starts 10 minutes out of the yard, the others warmed up; the model is not told.
    EXPECT_EQ(d.drives[0].driven_before.count(), 600.0);
    EXPECT_EQ(d.drives[2].driven_before, sim::kReportWarmUp);
    EXPECT_EQ(d.models[0].driven_before, sim::kReportWarmUp);
  }
  EXPECT_EQ(days.value()[1].road, "th10");
  // TH 10's morning run is driven at 45 mph against a 55 mph model.
  EXPECT_NEAR(days.value()[1].drives[0].speed_mps, 45 * 0.44704, 1e-9);
  EXPECT_NEAR(days.value()[1].models[0].speed_mps, 55 * 0.44704, 1e-9);
}

TEST(GapBenchDays, AWrongFieldIsNamedWithItsLine) {
  const auto path = std::filesystem::temp_directory_path() / "roadload-bench-days-test.toml";
  std::ofstream(path) << "[[day]]\nroad = \"x\"\n[[day.run]]\nlabel = \"a\"\nscenario = \"th66-55mph\"\nmode = \"coast\"\n"
                         "speed_mph = 40\n";
  const auto days = load_bench_days(path.string(), ROADLOAD_CONFIG_DIR);
  ASSERT_FALSE(days);
  EXPECT_EQ(days.error().line, 7);
  EXPECT_EQ(days.error().field, "day.run.speed_mph");
  std::ofstream(path) << "[[day]]\nroad = \"x\"\n[[day.run]]\nlabel = \"a\"\nscenario = \"th66-55mph\"\ndriven_before_s = -1\n";
  const auto cold = load_bench_days(path.string(), ROADLOAD_CONFIG_DIR);
  ASSERT_FALSE(cold);
  EXPECT_EQ(cold.error().line, 6);
  EXPECT_EQ(cold.error().field, "day.run.driven_before_s");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace roadload::gap
