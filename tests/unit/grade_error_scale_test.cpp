// The grade error's correlation length measured from the passes' scatter: a Gauss-Markov slope
// error gives back its own length, the slope of white height noise (which cancels over a block)
// a length near a bin's, and too little data gives nothing rather than a guess.
#include "roadload/grade_error_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace roadload {
namespace {

constexpr double kBin_m = 10.0;

// Passes whose slopes are a common truth (which the residuals remove) plus each pass's own
// Gauss-Markov error of correlation length l along the road.
std::vector<std::vector<double>> gauss_markov_passes(std::size_t passes, std::size_t bins, double l_m, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  const double phi = std::exp(-kBin_m / l_m), sigma = 0.001;
  std::vector<std::vector<double>> slopes(passes, std::vector<double>(bins));
  for (auto& pass : slopes) {
    double e = sigma * n01(rng);
    for (std::size_t k = 0; k < bins; ++k) {
      pass[k] = 0.01 * std::sin(static_cast<double>(k) / 40.0) + e;
      e = phi * e + sigma * std::sqrt(1 - phi * phi) * n01(rng);
    }
  }
  return slopes;
}

TEST(GradeErrorScale, AGaussMarkovErrorGivesBackItsLength) {
  for (double l_m : {20.0, 40.0, 80.0}) {
    double sum = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      const auto l = measured_grade_error_correlation_m(gauss_markov_passes(4, 2000, l_m, seed), {kBin_m, 600.0, 8});
      ASSERT_TRUE(l.has_value());
      sum += *l;
    }
    std::printf("Gauss-Markov slope error of %.0f m: measured %.1f m (mean of 8 seeds)\n", l_m, sum / 8);
    EXPECT_NEAR(sum / 8, l_m, 0.2 * l_m);
  }
}

TEST(GradeErrorScale, TheSlopeOfWhiteHeightNoiseCancelsOverABlock) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  constexpr int kHalf = 6;  // slope over +-60 m of 10 m bins
  std::vector<std::vector<double>> slopes(4, std::vector<double>(2000, std::nan("")));
  for (auto& pass : slopes) {
    std::vector<double> h(2000);
    for (double& x : h) x = 0.1 * n01(rng);
    for (std::size_t k = kHalf; k + kHalf < h.size(); ++k) {
      double num = 0, den = 0;
      for (int j = -kHalf; j <= kHalf; ++j) {
        num += j * kBin_m * h[k + static_cast<std::size_t>(j + kHalf) - kHalf];
        den += j * kBin_m * j * kBin_m;
      }
      pass[k] = num / den;
    }
  }
  const auto l = measured_grade_error_correlation_m(slopes, {kBin_m, 600.0, 8});
  ASSERT_TRUE(l.has_value());
  std::printf("slopes of white height noise: measured %.1f m\n", *l);
  EXPECT_LT(*l, 2 * kBin_m);
}

TEST(GradeErrorScale, TooFewBlocksOrPassesGiveNothing) {
  EXPECT_FALSE(measured_grade_error_correlation_m(gauss_markov_passes(1, 2000, 40, 1), {}).has_value());
  EXPECT_FALSE(measured_grade_error_correlation_m(gauss_markov_passes(2, 200, 40, 1), {kBin_m, 600.0, 8}).has_value());
}

TEST(GradeErrorScale, TheMeanVarianceShareIsTheGaussMarkovs) {
  EXPECT_NEAR(gauss_markov_mean_variance_share(10, 1000), 0.02 * (1 - 0.01), 1e-9);
  EXPECT_NEAR(gauss_markov_mean_variance_share(1e6, 1000), 1.0, 1e-3);
}

}  // namespace
}  // namespace roadload
