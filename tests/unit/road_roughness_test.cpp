// The road's roughness in the speed: ISO 8608's height from IRI, and the truck's ripple from its
// axles (road_roughness.hpp).
#include "roadload/model/road_roughness.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace roadload::model {
namespace {

TEST(RoadRoughness, TheHeightsPsdMeetsIso8608sSlopeWellAboveItsCorner) {
  const double iri = 2.65, l = 30.0;
  const double s = roughness_height_sigma_m(iri, l);
  // One-sided Gauss-Markov PSD at n = 1 cycle/m against G_d(n0) (n0 / n)^2.
  const double n = 1.0;
  const double psd = 4 * s * s * l / (1 + std::pow(2 * std::numbers::pi * n * l, 2));
  EXPECT_NEAR(psd, iso8608_gd_m3(iri) * 0.1 * 0.1 / (n * n), 1e-3 * psd);
  EXPECT_NEAR(iso8608_gd_m3(0.543), 1e-6, 1e-15);
  // TH 66's IRI: 8.4 mm of height below 30 m waves.
  EXPECT_NEAR(s, 0.0084, 0.0001);
}

TEST(RoadRoughness, OneAxleRipplesByGTimesItsHeightOverTheSpeedAndFarAxlesAddAsIndependent) {
  const std::array<AxleWeight, 1> one{{{0.0, 9.80665 * 1000}}};
  const RoughnessRipple r1 = roughness_ripple(one, 1000, 0.01, 30, 2.5);
  EXPECT_NEAR(r1.sigma_m2ps, 9.80665 * 0.01, 1e-12);
  EXPECT_NEAR(r1.correlation_m, 30, 1e-12);
  const std::array<AxleWeight, 2> apart{{{0.0, 500}, {1e6, 500}}};
  const RoughnessRipple r2 = roughness_ripple(apart, 100, 0.01, 30, 2.5);
  EXPECT_NEAR(r2.sigma_m2ps, std::sqrt(2.0) * 500 * 0.01 / 100, 1e-12);
  EXPECT_NEAR(r2.correlation_m, 30, 1e-9);
}

// Five axles each on its own Gauss-Markov height, correlated as they are along one road: the sum's
// sigma and its change over one step are the lumped process's.
TEST(RoadRoughness, TheLumpedRippleMatchesFiveAxlesOnOneSampledRoad) {
  const std::array<AxleWeight, 5> axles{{{0.0, 52000}, {5.14, 75800}, {6.46, 75800}, {16.45, 75400}, {17.69, 75400}}};
  const double l = 30.0, s = 0.008, mass = 36152, dx = 0.1;
  const std::size_t step = 25;  // 2.5 m: one tick at 55 mph
  const RoughnessRipple r = roughness_ripple(axles, mass, s, l, static_cast<double>(step) * dx);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> unit;
  const double phi = std::exp(-dx / l);
  // The road's height on a grid of dx, long enough for many correlation lengths.
  const std::size_t n = 2'000'000;
  std::vector<double> h(n);
  h[0] = s * unit(rng);
  for (std::size_t i = 1; i < n; ++i) h[i] = phi * h[i - 1] + s * std::sqrt(1 - phi * phi) * unit(rng);
  const std::size_t back = static_cast<std::size_t>(std::lround(17.69 / dx));
  const auto sum_at = [&](std::size_t i) {
    double v = 0;
    for (const AxleWeight& a : axles) v += a.weight_n * h[i + back - static_cast<std::size_t>(std::lround(a.behind_front_m / dx))];
    return v / mass;
  };
  double var = 0, dvar = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + back + step < n; i += step) {
    const double a = sum_at(i), b = sum_at(i + step);
    var += a * a;
    dvar += (b - a) * (b - a);
    ++count;
  }
  var /= static_cast<double>(count);
  dvar /= static_cast<double>(count);
  EXPECT_NEAR(std::sqrt(var), r.sigma_m2ps, 0.05 * r.sigma_m2ps);
  const double lumped = 2 * r.sigma_m2ps * r.sigma_m2ps * (1 - std::exp(-static_cast<double>(step) * dx / r.correlation_m));
  EXPECT_NEAR(dvar, lumped, 0.05 * lumped);
}

}  // namespace
}  // namespace roadload::model
