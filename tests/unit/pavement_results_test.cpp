// The answer per pavement type: one estimate over every usable tick on the type's cells together,
// not an average of the cells' estimates; live, the estimate says it needs the smoothed drive.
#include <gtest/gtest.h>

#include <numeric>

#include "roadload/cell_estimates.hpp"

namespace roadload {
namespace {

// Three 100 m cells; cells 0 and 2 are one pavement, cell 1 another.
PavementGroups two_pavements() { return {{"bituminous", "concrete"}, {0, 0}, {0, 1, 0}}; }

CellLimits limits() {
  CellLimits l;
  l.weight_n = 3.5e5;
  l.interval_z = 1.645;
  l.identified_sigma = 1e-3;
  return l;
}

// Ticks every 1 m at 20 m/s over the three cells (a point truck), each tick its own step.
void drive(CellEstimates& cells) {
  for (std::size_t step = 0; step < 300; ++step) {
    const double s = static_cast<double>(step) + 0.5;
    cells.tick(s, s, 20.0, Unusable::none, {0.006, 5e-4}, step);
  }
}

TEST(PavementResults, OneEstimateOverAllTheTypesTicks) {
  CellEstimates cells({{"a", 0, 100}, {"b", 100, 200}, {"c", 200, 300}}, 0.0, true);
  drive(cells);
  std::vector<std::size_t> seen;
  // The "mean" records which steps it was given and returns their mean index as the CRR.
  const auto mean = [&](std::size_t, std::span<const std::size_t> steps) {
    seen.assign(steps.begin(), steps.end());
    const double m = std::accumulate(steps.begin(), steps.end(), 0.0) / static_cast<double>(steps.size());
    return CrrMean{m * 1e-5, 1e-4};
  };
  const auto out = cells.group_results(two_pavements(), limits(), mean);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].id, "bituminous");
  EXPECT_EQ(out[0].samples, 200u);
  EXPECT_DOUBLE_EQ(out[0].end_m - out[0].start_m, 200.0);
  // Steps 0..99 and 200..299: mean index 149.5.
  EXPECT_NEAR(out[0].crr, 149.5e-5, 1e-12);
  EXPECT_EQ(out[1].id, "concrete");
  EXPECT_EQ(out[1].samples, 100u);
  EXPECT_NEAR(out[1].crr, 149.5e-5, 1e-12);  // steps 100..199
  EXPECT_EQ(seen.size(), 100u);
  EXPECT_NEAR(out[0].crr_hi - out[0].crr_lo, 2 * 1.645 * 1e-4, 1e-12);
  EXPECT_NEAR(out[0].speed_mps, 20.0, 1e-12);
}

TEST(PavementResults, LiveSaysItNeedsTheSmoothedDrive) {
  CellEstimates cells({{"a", 0, 100}, {"b", 100, 200}, {"c", 200, 300}}, 0.0, false);
  drive(cells);
  const auto out = cells.group_results(two_pavements(), limits(),
                                       [](std::size_t, std::span<const std::size_t>) { return CrrMean{}; });
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FALSE(out[0].identified);
  EXPECT_NE(out[0].reason.find("smoothed"), std::string::npos) << out[0].reason;
}

TEST(PavementResults, APavementNotDrivenSaysSo) {
  CellEstimates cells({{"a", 0, 100}, {"b", 100, 200}, {"c", 200, 300}}, 0.0, true);
  const auto out = cells.group_results(two_pavements(), limits(), [](std::size_t, std::span<const std::size_t>) {
    return CrrMean{0.006, 1e-4};
  });
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].samples, 0u);
  EXPECT_EQ(out[1].reason, "not driven");
}

}  // namespace
}  // namespace roadload
