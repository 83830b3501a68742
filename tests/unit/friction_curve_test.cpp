// The friction curve through EEC3's whole-percent steps: the crossings of a rounded smooth curve
// put it back to a fraction of one step, and too few steps give no curve at all.
#include <gtest/gtest.h>

#include <cmath>

#include "roadload/engine_loss_calibration.hpp"

namespace roadload {
namespace {

constexpr double kStepNm = 23.86;  // 1 % of the MnROAD engine's reference torque

double friction_pct(double rpm, double a) {
  const double k = rpm / 1000.0;
  return a + 2.0 * k + k * k;
}

std::vector<EngineLossHold> staircase(double a, double from_rpm, double to_rpm, double step_rpm) {
  std::vector<EngineLossHold> holds;
  for (double rpm = from_rpm; rpm <= to_rpm + 1e-9; rpm += step_rpm) {
    EngineLossHold h;
    h.point.rpm = rpm;
    h.eec3_friction_nm = std::round(friction_pct(rpm, a)) * kStepNm;
    holds.push_back(h);
  }
  return holds;
}

TEST(FrictionCurve, CrossingsOfTheRoundedCurveFindItToAFractionOfOneStep) {
  for (const double a : {3.7, 4.0, 4.3}) {
    // The engine-losses scenario's holds: 650-1,900 rpm every 25 rpm; the curve crosses five or six
    // half percents.
    const auto curve = fit_friction_curve(staircase(a, 650, 1900, 25));
    ASSERT_TRUE(curve.has_value()) << a;
    EXPECT_GE(curve->crossings, 5u) << a;
    double worst = 0;
    for (double rpm = 700; rpm <= 1850; rpm += 10) {
      worst = std::max(worst, std::abs(curve->at(rpm) - friction_pct(rpm, a) * kStepNm));
    }
    // Half a step is what EEC3 itself may miss by at any one speed.
    EXPECT_LT(worst, 0.06 * kStepNm) << a;
  }
}

TEST(FrictionCurve, FewerThanThreeStepsGiveNoCurve) {
  EXPECT_FALSE(fit_friction_curve(staircase(4.0, 1000, 1200, 50)).has_value());
  EXPECT_FALSE(fit_friction_curve({}).has_value());
}

}  // namespace
}  // namespace roadload
