// The friction curve through EEC3's whole-percent steps: the crossings of a rounded smooth curve
// put it back to a fraction of one step, and too few steps give no curve at all.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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

TEST(FrictionCurve, TheSplitSmoothsEachHoldsRoundingOutOfTheAccessories) {
  // Accessories of 4.2 kW: 34 N m at 1,200 rpm. Each hold's loss carries a rounding error of up to
  // +-1.5 N m that changes from hold to hold.
  const FrictionCurve curve{95.4, 47.7, 23.9, 6};
  std::vector<EngineLossHold> holds;
  for (int i = 0; i < 51; ++i) {
    EngineLossHold h;
    h.point.rpm = 650.0 + 25.0 * i;
    const double rounding = 1.5 * std::sin(2.3 * i);
    h.point.loss_nm = curve.at(h.point.rpm) + 4200.0 / (h.point.rpm * 2 * std::numbers::pi / 60) + rounding;
    holds.push_back(h);
  }
  split_losses(curve, holds);
  double worst = 0, sum_sq = 0;
  for (const EngineLossHold& h : holds) {
    const double accessories = 4200.0 / (h.point.rpm * 2 * std::numbers::pi / 60);
    const double e = h.point.loss_nm - h.point.friction_nm - accessories;
    worst = std::max(worst, std::abs(e));
    sum_sq += e * e;
  }
  // Unsmoothed, the worst hold would be 1.5 N m off and the RMS 1.06.
  EXPECT_LT(worst, 1.0);
  EXPECT_LT(std::sqrt(sum_sq / static_cast<double>(holds.size())), 0.5);
}

TEST(FrictionCurve, FewerThanThreeStepsGiveNoCurve) {
  EXPECT_FALSE(fit_friction_curve(staircase(4.0, 1000, 1200, 50)).has_value());
  EXPECT_FALSE(fit_friction_curve({}).has_value());
}

}  // namespace
}  // namespace roadload
