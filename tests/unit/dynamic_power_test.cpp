// Eq. 2.7-2.8 and Table 6.6: power from an acceleration density, and what it costs a year.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::spectra {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The report's Table 6.6 from its power column: 2,207 h/year, 120,000 miles/year, 36.4 MJ/L.
TEST(AnnualCost, ReproducesTable66FromItsPowerColumn) {
  const Duty duty;  // the report's: 2,207 h and 120,000 miles a year
  constexpr double kReportDieselJpl = 36.4e6;
  struct Row {
    double watts, mj, liters, l100;
  };
  for (const Row& r : {Row{6486, 51530, 1416, 0.7}, Row{9353, 74308, 2041, 1.1}, Row{2867, 22778, 626, 0.3}}) {
    const AnnualCost c = annual_cost(r.watts, duty, kReportDieselJpl);
    EXPECT_EQ(c.hours_per_year, 2207);
    EXPECT_NEAR(c.energy_mj_per_year, r.mj, r.mj * 0.001) << r.watts << " W";
    EXPECT_NEAR(c.diesel_l_per_year, r.liters, r.liters * 0.001) << r.watts << " W";
    EXPECT_EQ(std::round(c.l_per_100km * 10) / 10, r.l100) << r.watts << " W: " << c.l_per_100km;
  }
}

TEST(StretchCost, LitresPer100KmAreLitresOverDistance) {
  const StretchCost c = stretch_cost(650.0, 10.0, 13.41, 35.8e6);
  EXPECT_DOUBLE_EQ(c.energy_j, 6500.0);
  EXPECT_DOUBLE_EQ(c.diesel_l, 6500.0 / 35.8e6);
  EXPECT_NEAR(c.l_per_100km, c.diesel_l / (13.41 * 10.0) * 1e5, 1e-12);
}

// A sinusoidal relative velocity of amplitude V through a dashpot d dissipates d V^2 / 2. Its
// acceleration has amplitude 2 pi f V; the density integral must return d V^2 / 2, not 2 pi times it.
TEST(DashpotPower, ASineGivesHalfDampingTimesVelocityAmplitudeSquared) {
  const double fs = 200.0, f0 = 12.5, v_amp = 0.02, d = 20000.0;
  const WelchConfig c{fs, 512, 384};
  WelchPsd psd(c);
  for (int i = 0; i < 40000; ++i) psd.push(kTwoPi * f0 * v_amp * std::cos(kTwoPi * f0 * i / fs));
  std::vector<double> s(psd.bins());
  psd.density(s);
  // Hann spreads the line over its neighbours at f0 +- 0.39 Hz, weighted 1/f^2 there: +0.1 %.
  EXPECT_NEAR(dashpot_power_w(d, s, bin_hz(c)), d * v_amp * v_amp / 2, 2e-3 * d * v_amp * v_amp / 2);
  EXPECT_NEAR(dashpot_power_w(d, s, bin_hz(c), {13.5, 1e9}), 0.0, 1e-9);  // the line lies below the band
}

TEST(TireDeflectionPower, MatchesTheSpringDashpotDrivenByAKnownForce) {
  // F = F0 sin(w t) on k || c: x' amplitude F0 w / |k + i w c|, power c x'^2 / 2.
  const double fs = 200.0, f0 = 10.0, f_amp = 3000.0, k = 2.0e6, c = 8000.0;
  const WelchConfig cfg{fs, 400, 300};
  WelchPsd psd(cfg);
  for (int i = 0; i < 40000; ++i) psd.push(f_amp * std::sin(kTwoPi * f0 * i / fs));
  std::vector<double> s(psd.bins());
  psd.density(s);
  const double w = kTwoPi * f0;
  const double xdot = f_amp * w / std::hypot(k, w * c);
  EXPECT_NEAR(tire_deflection_power_w(c, k, s, bin_hz(cfg)), c * xdot * xdot / 2, 1e-3 * c * xdot * xdot);
}

}  // namespace
}  // namespace roadload::spectra
