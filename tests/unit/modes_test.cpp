// Peaks with their prominence and width, band labels, and the joint comb on synthetic spectra.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "roadload/spectra/modes.hpp"

namespace roadload::spectra {
namespace {

// A Lorentzian of half width at half maximum `hwhm` on a flat floor.
std::vector<double> two_modes(double bin) {
  std::vector<double> d(400);
  for (std::size_t k = 0; k < d.size(); ++k) {
    const double f = static_cast<double>(k) * bin;
    d[k] = 0.01 + 1.0 / (1 + std::pow((f - 1.5) / 0.1, 2)) + 0.3 / (1 + std::pow((f - 12.3) / 0.4, 2));
  }
  return d;
}

TEST(FindPeaks, FrequencyProminenceAndWidthOfTwoModes) {
  const double bin = 0.05;
  const auto peaks = find_peaks(two_modes(bin), bin);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_NEAR(peaks[0].freq, 1.5, bin);
  EXPECT_NEAR(peaks[0].width, 0.2, 0.02);  // full width at half prominence = 2 x hwhm
  EXPECT_EQ(peaks[0].label, "rigid body");
  EXPECT_NEAR(peaks[1].freq, 12.3, bin);
  EXPECT_NEAR(peaks[1].width, 0.8, 0.05);
  EXPECT_NEAR(peaks[1].prominence, 0.3, 0.02);
  EXPECT_EQ(peaks[1].label, "tandem");
}

TEST(ModeBand, LabelsFollowTheReportsBands) {
  EXPECT_EQ(mode_band(2.9), "rigid body");
  EXPECT_EQ(mode_band(4.5), "bounce/pitch");
  EXPECT_EQ(mode_band(11.7), "tandem");
  EXPECT_EQ(mode_band(17.5), "roll");
}

// Rough-road background falling as k^-2, chi-square scatter of 10 averaged segments, and optional
// lines at h / L of `line_ratio` times the background.
std::vector<double> road(double bin, double panel_m, double line_ratio, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::gamma_distribution<double> scatter(10.0, 0.1);
  std::vector<double> d(2049);
  for (std::size_t j = 1; j < d.size(); ++j) {
    const double k = static_cast<double>(j) * bin;
    d[j] = 1e-6 / (k * k) * scatter(rng);
    if (panel_m > 0) {
      const double h = k * panel_m;
      if (std::round(h) >= 1 && std::abs(h - std::round(h)) / panel_m < 0.6 * bin) d[j] *= line_ratio;
    }
  }
  return d;
}

TEST(FindJointLine, FindsFifteenFootPanelsBlind) {
  const double bin = 1.0 / (4096 * 0.08);
  const std::vector<std::vector<double>> ch = {road(bin, 4.572, 3.0, 1), road(bin, 4.572, 3.0, 2)};
  const JointLine j = find_joint_line(ch, bin);
  ASSERT_TRUE(j.found);
  EXPECT_NEAR(j.panel_m, 4.572, 0.01 * 4.572);
  EXPECT_GE(j.harmonics, 5);
}

TEST(FindJointLine, NoLineWithoutJoints) {
  const double bin = 1.0 / (4096 * 0.08);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<std::vector<double>> ch = {road(bin, 0, 1, seed), road(bin, 0, 1, seed + 10)};
    EXPECT_FALSE(find_joint_line(ch, bin).found) << "seed " << seed;
  }
}

TEST(FindJointLine, GuidedSearchStaysNearTheInventory) {
  const double bin = 1.0 / (4096 * 0.08);
  const std::vector<std::vector<double>> ch = {road(bin, 8.5344, 1.6, 3)};
  JointConfig guided;
  guided.expected_panel_m = 8.5;
  const JointLine j = find_joint_line(ch, bin, guided);
  ASSERT_TRUE(j.found);
  EXPECT_NEAR(j.panel_m, 8.5344, 0.02 * 8.5344);
}

}  // namespace
}  // namespace roadload::spectra
