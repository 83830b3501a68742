#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "roadload/sim/iri.hpp"

namespace roadload::sim {
namespace {

// Golden Car per unit sprung mass (ASTM E1926) and the IRI speed.
constexpr double kK1 = 653.0, kK2 = 63.3, kMu = 0.15, kC = 6.0;
constexpr double kSpeed_mps = 80.0 / 3.6;

// Suspension stroke z_s - z_u per unit road height, from the equations of motion
//   z_s'' = -k2 (z_s - z_u) - c (z_s' - z_u'),  mu z_u'' = k2 (z_s - z_u) + c (z_s' - z_u') - k1 (z_u - y).
// The same function maps the road slope to the stroke rate over speed that the IRI averages.
std::complex<double> stroke_per_height(double omega_rad_s) {
  const std::complex<double> s(0.0, omega_rad_s);
  const auto body = s * s + kC * s + kK2;
  const auto link = kC * s + kK2;
  return -kK1 * s * s / (body * (kMu * s * s + link + kK1) - link * link);
}

TEST(Iri, MappingToIsoClasses) {
  EXPECT_NEAR(iri_from_gd_m_per_km(16e-6), 2.172, 1e-12);
  EXPECT_NEAR(gd_from_iri_m3(2.55), 22.05e-6, 0.01e-6);  // TH 10, parameter sheet 6.1
  EXPECT_NEAR(gd_from_iri_m3(iri_from_gd_m_per_km(64e-6)), 64e-6, 1e-18);
}

TEST(Iri, FlatRoadIsZeroAndTooShortIsUndefined) {
  const ProfileSegment seg{0.0, 1000.0, 0.0, {}};
  const auto p = RoadProfile::generate({&seg, 1}, 0.0, 1000.0, 1);
  EXPECT_EQ(iri_m_per_km(p, 0.0, 1000.0), 0.0);
  EXPECT_TRUE(std::isnan(iri_m_per_km(p, 100.0, 100.2)));
}

// A sinusoid: the 250 mm moving average scales the slope by sin(pi b / lambda) / (pi b / lambda),
// the car answers with |H| at 2 pi V / lambda, and the mean of |sin| is 2 / pi.
TEST(Iri, SinusoidMatchesTheGoldenCarSteadyState) {
  constexpr double kDx = 0.025, kBase = 0.25, kAmplitude = 0.002, kLength = 2000.0;
  for (const double wavelength : {1.0, 2.5, 5.0, 20.0}) {
    std::vector<double> z;
    for (double i = 0; i * kDx <= kLength; ++i) {
      z.push_back(kAmplitude * std::sin(2 * std::numbers::pi * i * kDx / wavelength));
    }
    const auto p = RoadProfile::from_samples(z, 0.0, kDx);
    const double slope = 2 * kAmplitude * std::sin(std::numbers::pi * kBase / wavelength) / kBase;
    const double gain = std::abs(stroke_per_height(2 * std::numbers::pi * kSpeed_mps / wavelength));
    const double expected = 1000.0 * (2 / std::numbers::pi) * gain * slope;
    const double iri = iri_m_per_km(p, 0.0, kLength);
    RecordProperty("sinusoid_" + std::to_string(wavelength) + "_ratio", std::to_string(iri / expected));
    EXPECT_NEAR(iri / expected, 1.0, 0.005) << wavelength << " m: " << iri << " vs " << expected;
  }
}

// Parameter sheet check 7: a random profile made for an IRI has that IRI within 5 %.
TEST(Iri, RandomProfileHasTheIriItWasMadeFor) {
  constexpr double kLength = 10000.0;
  for (const double target : {2.55, 2.65, iri_from_gd_m_per_km(64e-6)}) {
    const ProfileSegment seg{0.0, kLength, gd_from_iri_m3(target), {}};
    const auto p = RoadProfile::generate({&seg, 1}, 0.0, kLength, 2024);
    const double iri = iri_m_per_km(p, 0.0, kLength);
    RecordProperty("iri_" + std::to_string(target), std::to_string(iri));
    EXPECT_NEAR(iri / target, 1.0, 0.05) << target << " m/km: " << iri;
  }
}

}  // namespace
}  // namespace roadload::sim
