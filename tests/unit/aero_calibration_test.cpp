// CdA from two drives at two speeds, on cells whose estimates follow the linear model the fit
// assumes: each drive's CRR moves with CdA by its own sensitivity, the cells' CRR is shared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "roadload/aero_calibration.hpp"

namespace roadload {
namespace {

constexpr double kTrueCda = 6.35;
constexpr double kPrior = 6.2;

// One drive over cells at a speed whose drag per m^2 of CdA is `drag_per_m2` in CRR.
struct DriveSpec {
  std::size_t cells = 29;
  double drag_per_m2 = 0;
  double noise = 5e-5;          // each cell's error, white along the road unless `correlation`
  double stated_sigma = 5e-5;   // what each cell says its sigma is
  double correlation = 0;       // of neighbouring cells' errors
  double torque_per_nm = 2e-5;  // CRR per N m of flywheel torque (the gear's)
  double torque_bias_nm = 0;    // true less computed flywheel torque
  double crr_per_scale = 0;     // CRR per unit of the ECU's torque scale; 0: no scale run
};

constexpr double kScaleStep = 0.04;

AeroDrive drive(const DriveSpec& spec, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  AeroDrive d;
  double error = spec.noise * gauss(rng);
  for (std::size_t i = 0; i < spec.cells; ++i) {
    if (i > 0) error = spec.correlation * error + std::sqrt(1 - spec.correlation * spec.correlation) * spec.noise * gauss(rng);
    const double crr = 0.005 + 0.0002 * static_cast<double>(i % 7);
    CellResult held;
    held.samples = 100;
    held.crr_sigma = spec.stated_sigma;
    // A missing flywheel torque is read as less rolling resistance.
    held.crr = crr + spec.drag_per_m2 * (kTrueCda - kPrior) - spec.torque_per_nm * spec.torque_bias_nm + error;
    CellResult cda = held;
    cda.crr -= spec.drag_per_m2 * kCdaStep_m2;
    CellResult torque = held;
    torque.crr += spec.torque_per_nm;
    d.held.push_back(held);
    d.cda.push_back(cda);
    d.torque.push_back(torque);
    if (spec.crr_per_scale != 0) {
      CellResult scale = held;
      scale.crr += spec.crr_per_scale * kScaleStep;
      d.scale.push_back(scale);
      d.scale_step = kScaleStep;
    }
  }
  return d;
}

AeroDrive drive(std::size_t n, double drag_per_m2, double noise, std::mt19937& rng) {
  return drive({.cells = n, .drag_per_m2 = drag_per_m2, .noise = noise, .stated_sigma = noise}, rng);
}

// 30 and 64 mph on the 36 t truck: 0.5 rho v^2 / (m g) per m^2 of CdA.
constexpr double kSlow = 0.5 * 1.2 * 13.4 * 13.4 / 356000, kFast = 0.5 * 1.2 * 28.6 * 28.6 / 356000;

TEST(AeroCalibration, RecoversCdaFromTwoSpeedsWithinItsSigma) {
  std::mt19937 rng(7);
  int inside = 0;
  for (int run = 0; run < 40; ++run) {
    const AeroDrive a = drive(29, kSlow, 5e-5, rng), b = drive(29, kFast, 5e-5, rng);
    const AeroCalibration fit = fit_cda(a, b, kPrior, 0.0);
    ASSERT_EQ(fit.cells, 29u);
    EXPECT_GT(fit.sigma_m2, 0.005);
    EXPECT_LT(fit.sigma_m2, 0.05);
    if (std::abs(fit.cda_m2 - kTrueCda) < 2 * fit.sigma_m2) ++inside;
  }
  EXPECT_GE(inside, 36);  // 95 % of 40, less a little chance
}

TEST(AeroCalibration, PairsOfBothDirectionsFitOneCdaWithBothTheirCells) {
  // The road both ways: two pairs of 5 cells each, their errors drawn alike. One fit over both
  // counts 10 cells and is as good as, on average, the better of two separate ones.
  std::mt19937 rng(11);
  double joint_sq = 0, east_sq = 0;
  constexpr int kRuns = 100;
  for (int run = 0; run < kRuns; ++run) {
    const AeroDrive es = drive(5, kSlow, 5e-5, rng), ef = drive(5, kFast, 5e-5, rng);
    const AeroDrive ws = drive(5, kSlow, 5e-5, rng), wf = drive(5, kFast, 5e-5, rng);
    const AeroPair pairs[] = {{&es, &ef}, {&ws, &wf}};
    const AeroCalibration joint = fit_cda(pairs, kPrior, 0.0);
    ASSERT_EQ(joint.cells, 10u);
    joint_sq += std::pow(joint.cda_m2 - kTrueCda, 2) / kRuns;
    east_sq += std::pow(fit_cda(es, ef, kPrior, 0.0).cda_m2 - kTrueCda, 2) / kRuns;
  }
  std::printf("RMS CdA error: one pair %.4f, both pairs %.4f m^2\n", std::sqrt(east_sq), std::sqrt(joint_sq));
  EXPECT_LT(std::sqrt(joint_sq), 0.85 * std::sqrt(east_sq));  // sqrt(1/2) of it, less the chance of 100 runs
}

// Over 200 calibrations, the fraction of errors within 2 sigma, and the RMS of error over sigma.
struct Coverage {
  double inside = 0, rms = 0, correlation = 0;
};

Coverage coverage(const DriveSpec& slow, const DriveSpec& fast, std::mt19937& rng) {
  Coverage c;
  constexpr int kRuns = 200;
  for (int run = 0; run < kRuns; ++run) {
    const AeroCalibration fit = fit_cda(drive(slow, rng), drive(fast, rng), kPrior, 0.0);
    const double z = (fit.cda_m2 - kTrueCda) / fit.sigma_m2;
    c.inside += std::abs(z) < 2 ? 1.0 / kRuns : 0.0;
    c.rms += z * z / kRuns;
    c.correlation += fit.residual_correlation / kRuns;
  }
  c.rms = std::sqrt(c.rms);
  return c;
}

TEST(AeroCalibration, TheCellsScatterSizesTheSigmaWhenTheirOwnSigmasOverstateIt) {
  std::mt19937 rng(10);
  const Coverage c = coverage({.drag_per_m2 = kSlow, .stated_sigma = 1.5e-4}, {.drag_per_m2 = kFast, .stated_sigma = 1.5e-4}, rng);
  EXPECT_GT(c.inside, 0.90);
  EXPECT_GT(c.rms, 0.8);  // not three times too wide, as the stated sigmas would make it
  EXPECT_LT(c.rms, 1.25);
}

TEST(AeroCalibration, CorrelatedNeighboursWidenTheSigma) {
  std::mt19937 rng(11);
  const DriveSpec slow{.drag_per_m2 = kSlow, .correlation = 0.6}, fast{.drag_per_m2 = kFast, .correlation = 0.6};
  const Coverage c = coverage(slow, fast, rng);
  std::printf("AR(1) 0.6 cells: estimated correlation %.2f, error/sigma RMS %.2f, within 2 sigma %.1f %%\n", c.correlation, c.rms,
              100 * c.inside);
  EXPECT_GT(c.correlation, 0.45);
  EXPECT_GT(c.inside, 0.88);
  EXPECT_LT(c.rms, 1.3);
}

TEST(AeroCalibration, ATorqueBiasMovesTheFittedCdaAsItsSensitivitySays) {
  std::mt19937 rng(12);
  // Fewer N m at the wheels per flywheel N m in the faster drive's higher gear.
  DriveSpec slow{.drag_per_m2 = kSlow, .noise = 1e-9, .stated_sigma = 5e-5, .torque_per_nm = 2e-5};
  DriveSpec fast{.drag_per_m2 = kFast, .noise = 1e-9, .stated_sigma = 5e-5, .torque_per_nm = 1.5e-5};
  const AeroCalibration unbiased = fit_cda(drive(slow, rng), drive(fast, rng), kPrior, 1.0);
  // CdA + b (t_slow - t_fast) / (s_slow - s_fast), the sensitivities to CdA being -drag.
  const double per_nm = (2e-5 - 1.5e-5) / (kFast - kSlow);
  EXPECT_NEAR(unbiased.cda_per_torque_bias_m2_per_nm, per_nm, 1e-9);
  EXPECT_NEAR(unbiased.torque_m2, per_nm, 1e-9);
  EXPECT_NEAR(unbiased.sigma_m2, std::hypot(unbiased.statistical_m2, unbiased.torque_m2), 1e-12);
  EXPECT_NEAR(unbiased.torque_bias_correlation, -per_nm / unbiased.sigma_m2, 1e-9);
  slow.torque_bias_nm = fast.torque_bias_nm = 3.0;
  const AeroCalibration biased = fit_cda(drive(slow, rng), drive(fast, rng), kPrior, 1.0);
  EXPECT_NEAR(biased.cda_m2 - kTrueCda, 3.0 * per_nm, 1e-4);
  // The same gear in both drives: the bias cancels, and nothing of it is in the sigma.
  fast.torque_per_nm = 2e-5;
  const AeroCalibration same = fit_cda(drive(slow, rng), drive(fast, rng), kPrior, 1.0);
  EXPECT_NEAR(same.cda_m2, kTrueCda, 1e-4);
  EXPECT_NEAR(same.torque_m2, 0.0, 1e-9);
}

// A torque the ECU overstates by s is read as s more of the whole road load, drag and rolling
// resistance alike: only the drag differs between the speeds, so the fit moves by s times CdA.
TEST(AeroCalibration, TheFittedCdaFollowsTheTorqueScaleByItsDragShare) {
  std::mt19937 rng(13);
  DriveSpec slow{.drag_per_m2 = kSlow, .noise = 1e-9, .stated_sigma = 5e-5, .crr_per_scale = 0.005 + kSlow * kTrueCda};
  DriveSpec fast{.drag_per_m2 = kFast, .noise = 1e-9, .stated_sigma = 5e-5, .crr_per_scale = 0.005 + kFast * kTrueCda};
  const AeroCalibration fit = fit_cda(drive(slow, rng), drive(fast, rng), kPrior, 1.0);
  EXPECT_NEAR(fit.cda_per_torque_scale_m2, kTrueCda, 1e-6);
  // Without the scale's run nothing is claimed about it.
  const AeroCalibration unscaled = fit_cda(drive(29, kSlow, 5e-5, rng), drive(29, kFast, 5e-5, rng), kPrior, 1.0);
  EXPECT_EQ(unscaled.cda_per_torque_scale_m2, 0.0);
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
