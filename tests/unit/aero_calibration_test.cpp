// CdA from two drives at two speeds, on cells whose estimates follow the linear model the fit
// assumes: each drive's CRR moves with CdA by its own sensitivity, the cells' CRR is shared.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadload/aero_calibration.hpp"

namespace roadload {
namespace {

constexpr double kTrueCda = 6.35;
constexpr double kPrior = 6.2;

// One drive over `n` cells at a speed whose drag per m^2 of CdA is `drag_per_m2` in CRR.
AeroDrive drive(std::size_t n, double drag_per_m2, double noise, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, noise);
  AeroDrive d;
  for (std::size_t i = 0; i < n; ++i) {
    const double crr = 0.005 + 0.0002 * static_cast<double>(i % 7);
    CellResult held;
    held.samples = 100;
    held.crr_sigma = noise;
    held.crr = crr + drag_per_m2 * (kTrueCda - kPrior) + gauss(rng);
    CellResult cda = held;
    cda.crr -= drag_per_m2 * kCdaStep_m2;
    CellResult torque = held;
    torque.crr += 2e-5;  // 1 N m at the flywheel
    d.held.push_back(held);
    d.cda.push_back(cda);
    d.torque.push_back(torque);
  }
  return d;
}

TEST(AeroCalibration, RecoversCdaFromTwoSpeedsWithinItsSigma) {
  std::mt19937 rng(7);
  // 30 and 64 mph on the 36 t truck: 0.5 rho v^2 / (m g) per m^2 of CdA.
  const double slow = 0.5 * 1.2 * 13.4 * 13.4 / 356000, fast = 0.5 * 1.2 * 28.6 * 28.6 / 356000;
  int inside = 0;
  for (int run = 0; run < 40; ++run) {
    const AeroDrive a = drive(29, slow, 5e-5, rng), b = drive(29, fast, 5e-5, rng);
    const AeroCalibration fit = fit_cda(a, b, kPrior, 0.0);
    ASSERT_EQ(fit.cells, 29u);
    EXPECT_GT(fit.sigma_m2, 0.005);
    EXPECT_LT(fit.sigma_m2, 0.05);
    if (std::abs(fit.cda_m2 - kTrueCda) < 2 * fit.sigma_m2) ++inside;
  }
  EXPECT_GE(inside, 36);  // 95 % of 40, less a little chance
}

TEST(AeroCalibration, AFlywheelTorqueErrorWidensTheSigmaByItsShare) {
  std::mt19937 rng(8);
  const double slow = 0.5 * 1.2 * 13.4 * 13.4 / 356000, fast = 0.5 * 1.2 * 28.6 * 28.6 / 356000;
  const AeroDrive a = drive(29, slow, 5e-5, rng), b = drive(29, fast, 5e-5, rng);
  const AeroCalibration without = fit_cda(a, b, kPrior, 0.0);
  const AeroCalibration with = fit_cda(a, b, kPrior, 1.0);
  EXPECT_DOUBLE_EQ(without.torque_m2, 0.0);
  // 1 N m each at 2e-5 in CRR, independent: sqrt(2) x 2e-5 over the speeds' difference per m^2.
  EXPECT_NEAR(with.torque_m2, std::sqrt(2.0) * 2e-5 / (fast - slow), 1e-3);
  EXPECT_NEAR(with.sigma_m2, std::hypot(with.statistical_m2, with.torque_m2), 1e-12);
}

TEST(AeroCalibration, OneSpeedCannotTellDragFromRollingResistance) {
  std::mt19937 rng(9);
  const double slow = 0.5 * 1.2 * 13.4 * 13.4 / 356000;
  const AeroDrive a = drive(29, slow, 5e-5, rng), b = drive(29, slow * 1.001, 5e-5, rng);
  EXPECT_EQ(fit_cda(a, b, kPrior, 0.0).cells, 0u);
  const AeroDrive few = drive(1, slow, 5e-5, rng);
  EXPECT_EQ(fit_cda(few, drive(1, 2 * slow, 5e-5, rng), kPrior, 0.0).cells, 0u);
}

}  // namespace
}  // namespace roadload
