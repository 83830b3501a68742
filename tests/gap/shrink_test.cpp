// The gap a diagnosis is asked to explain and the share of it the named effects removed: what the
// bench scores and what the verdict on a name requires.
#include <gtest/gtest.h>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {
namespace {

GapResult held_out(double before, double after) {
  GapResult g;
  g.chi2_before = before;
  g.chi2_after = after;
  g.null_chi2_mean = 200;
  g.null_chi2_sd = 50;
  return g;
}

TEST(GapShrink, IsTheShareOfTheGapBeyondTheNoiseTheEffectsRemoved) {
  EXPECT_TRUE(gap_visible(held_out(1000, 300)));
  EXPECT_DOUBLE_EQ(gap_shrink(held_out(1000, 300)), 1.0 - 100.0 / 800.0);
  // Down to the noise, or below it: the whole gap.
  EXPECT_DOUBLE_EQ(gap_shrink(held_out(1000, 150)), 1.0);
  // A sliver of a large gap, as a truck far from the model's leaves it.
  EXPECT_NEAR(gap_shrink(held_out(328952, 319545)), 0.0286, 0.0001);
}

TEST(GapShrink, AGapWithinFourNoiseDeviationsIsNotVisibleAndShrinksByNothing) {
  EXPECT_FALSE(gap_visible(held_out(400, 210)));
  EXPECT_EQ(gap_shrink(held_out(400, 210)), 0.0);
  // The noise drives' deviation counts as at least 10.
  GapResult g = held_out(245, 200);
  g.null_chi2_sd = 1;
  EXPECT_TRUE(gap_visible(g));
}

}  // namespace
}  // namespace roadload::gap
