// The torque scale from powered drives and coast-downs, on cells whose estimates follow the linear
// model the fit assumes: a powered cell's CRR moves with the scale the analysis holds, a coasting
// one's does not; both move with the CdA held, each by its own speed's drag.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadload/torque_scale_calibration.hpp"

namespace roadload {
namespace {

constexpr double kTrueScale = -0.04;  // true torque = EEC1's x (1 + scale)
constexpr double kStep = 0.05;
constexpr double kCells = 16;

struct Spec {
  double crr_per_scale = 0;  // tractive force over the weight: 0 when coasting
  double drag_per_m2 = 0;    // CRR per m^2 of CdA at the drive's speed
  double cda_error_m2 = 0;   // true less held
  double noise = 1e-4;
  double per_mass_sigma = 0;  // CRR per sigma of the mass's prior; 0: no mass run
};

AeroDrive drive(const Spec& spec, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  AeroDrive d;
  d.scale_step = kStep;
  for (int i = 0; i < kCells; ++i) {
    const double crr = 0.005 + 0.0003 * (i % 5);
    CellResult held;
    held.samples = 100;
    held.crr_sigma = spec.noise;
    // Held at scale 0 and at the prior CdA: the force the analysis leaves out is read as CRR.
    held.crr = crr - spec.crr_per_scale * kTrueScale + spec.drag_per_m2 * spec.cda_error_m2 + spec.noise * gauss(rng);
    CellResult scale = held, cda = held, torque = held;
    scale.crr += spec.crr_per_scale * kStep;
    cda.crr -= spec.drag_per_m2 * kCdaStep_m2;
    d.held.push_back(held);
    d.scale.push_back(scale);
    d.cda.push_back(cda);
    d.torque.push_back(torque);
    if (spec.per_mass_sigma != 0) {
      CellResult mass = held;
      mass.crr += spec.per_mass_sigma;
      d.mass.push_back(mass);
    }
  }
  return d;
}

// 55 mph powered, its tractive force 0.0145 of the weight; a coast-down from 65 mph averaging 50.
constexpr double kPoweredScale = 0.0145;
constexpr double kPoweredDrag = 0.5 * 1.2 * 24.6 * 24.6 / 356000, kCoastDrag = 0.5 * 1.2 * 22.4 * 22.4 / 356000;

TEST(TorqueScaleCalibration, RecoversTheScaleWithinItsSigma) {
  std::mt19937 rng(5);
  double z2 = 0;
  constexpr int kSeeds = 40;
  for (int k = 0; k < kSeeds; ++k) {
    const AeroDrive p = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag}, rng);
    const AeroDrive c = drive({.drag_per_m2 = kCoastDrag}, rng);
    const ScalePair pairs[] = {{&p, &c}};
    const TorqueScaleCalibration fit = fit_torque_scale(pairs, 0.0, 0.0);
    ASSERT_EQ(fit.cells, 16u);
    const double z = (fit.scale - kTrueScale) / fit.sigma;
    EXPECT_LT(std::abs(z), 3.5);
    z2 += z * z;
  }
  // The cells' noise is white: the scatter's sigma is the fit's error.
  EXPECT_NEAR(std::sqrt(z2 / kSeeds), 1.0, 0.35);
}

TEST(TorqueScaleCalibration, ACdaErrorPassesIntoTheScaleAsItsSensitivitySays) {
  std::mt19937 rng(6);
  constexpr double kError = 0.4;
  const AeroDrive p = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag, .cda_error_m2 = kError, .noise = 1e-7},
                            rng);
  const AeroDrive c = drive({.drag_per_m2 = kCoastDrag, .cda_error_m2 = kError, .noise = 1e-7}, rng);
  const ScalePair pairs[] = {{&p, &c}};
  const TorqueScaleCalibration fit = fit_torque_scale(pairs, 0.3, 0.0);
  // Held at the truth the fit would be exact; held kError below it, the fit is off by the slope.
  EXPECT_NEAR(fit.scale - kTrueScale, -fit.scale_per_cda_m2 * kError, 1e-5);
  EXPECT_NEAR(fit.scale_per_cda_m2, (kPoweredDrag - kCoastDrag) / kPoweredScale, 1e-6);
  EXPECT_NEAR(fit.cda, 0.3 * std::abs(fit.scale_per_cda_m2), 1e-9);
  EXPECT_GE(fit.sigma, fit.cda);
}

// The CdA held was fitted from two speeds at a scale of 0 and moves C m^2 per unit of scale: it is
// C kTrueScale off the truck's. Solved together, the scale and that CdA come out the truck's.
TEST(TorqueScaleCalibration, SolvedWithTheAeroFitBothComeOutTheTrucks) {
  std::mt19937 rng(8);
  constexpr double kPerScale = 4.8;
  const double cda_error = kPerScale * kTrueScale;  // true less held
  const AeroDrive p = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag, .cda_error_m2 = cda_error, .noise = 1e-7},
                            rng);
  const AeroDrive c = drive({.drag_per_m2 = kCoastDrag, .cda_error_m2 = cda_error, .noise = 1e-7}, rng);
  const ScalePair pairs[] = {{&p, &c}};
  const TorqueScaleCalibration alone = fit_torque_scale(pairs, 0.02, 0.0);
  const TorqueScaleCalibration joint = with_aero_coupling(alone, kPerScale);
  EXPECT_GT(std::abs(alone.scale - kTrueScale), 0.002);
  EXPECT_NEAR(joint.scale, kTrueScale, 1e-5);
  EXPECT_NEAR(joint.cda_shift_m2, cda_error, 1e-4);
  EXPECT_NEAR(joint.sigma, alone.sigma / (1 - alone.scale_per_cda_m2 * kPerScale), 1e-12);
  // A coupling that cancels the scale's own slope leaves nothing to solve.
  EXPECT_EQ(with_aero_coupling(alone, 1.0 / alone.scale_per_cda_m2).cells, 0u);
}

// A coast-down's CRR is its deceleration less the drag over the mass: a heavier prior takes less
// drag off it (0.0083 of the weight at 60 mph, 5 % of mass: -0.0004), a powered drive's barely moves.
TEST(TorqueScaleCalibration, TheMassPriorsSigmaPassesIntoTheScales) {
  std::mt19937 rng(9);
  const AeroDrive p = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag, .per_mass_sigma = 0.00005}, rng);
  const AeroDrive c = drive({.drag_per_m2 = kCoastDrag, .per_mass_sigma = -0.0004}, rng);
  const ScalePair pairs[] = {{&p, &c}};
  const TorqueScaleCalibration fit = fit_torque_scale(pairs, 0.0, 0.0);
  EXPECT_NEAR(fit.mass, 0.00045 / kPoweredScale, 1e-9);
  EXPECT_NEAR(fit.sigma, std::hypot(fit.statistical, fit.mass), 1e-12);
}

TEST(TorqueScaleCalibration, TwoDrivesThatMoveAlikeTellNothing) {
  std::mt19937 rng(7);
  const AeroDrive a = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag}, rng);
  const AeroDrive b = drive({.crr_per_scale = kPoweredScale, .drag_per_m2 = kPoweredDrag}, rng);
  const ScalePair pairs[] = {{&a, &b}};
  EXPECT_EQ(fit_torque_scale(pairs, 0.6, 0.0).cells, 0u);
}

}  // namespace
}  // namespace roadload
