// EEC1's torque scale carried by a second run: each estimate's sigma widens by how far the scale's
// one-sigma change moved it, the checks run again on the wider interval, and without a torque prior
// the drive is analysed once, as given.
#include "roadload/torque_scale_consider.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace roadload {
namespace {

CellResult cell(double crr, double sigma) {
  CellResult c;
  c.samples = 100;
  c.crr = crr;
  c.crr_sigma = sigma;
  c.identified = true;
  return c;
}

// A drive every drive check passes.
TripResult good_trip(double crr, double mass_kg) {
  TripResult t;
  t.ticks = t.usable_ticks = 1000;
  t.filter.updates = 1000;
  t.mean_nis = 1.0;
  t.mean_nis_se = 0.05;
  t.wind_samples = 10;
  t.gnss_used = 100;
  t.crr = crr;
  t.crr_sigma = 0.0002;
  t.mass_kg = mass_kg;
  t.mass_sigma_kg = 500;
  t.identified = true;
  return t;
}

TEST(TorqueScaleConsider, EachSigmaWidensByItsShiftAndTheChecksRunAgain) {
  AnalyzerConfig cfg;
  DriveAnalysis held{{cell(0.0060, 0.0003), cell(0.0050, 0.0005), CellResult{}},
                     good_trip(0.0055, 30000),
                     {PavementResult{cell(0.0060, 0.0003), 2, 0, 0}}};
  DriveAnalysis shifted{{cell(0.0064, 0.0003), cell(0.0042, 0.0005), CellResult{}},
                        good_trip(0.0057, 31200),
                        {PavementResult{cell(0.0064, 0.0003), 2, 0, 0}}};
  const DriveAnalysis out = widen_by_shift(held, shifted, cfg);
  EXPECT_NEAR(out.cells[0].crr_sigma, 0.0005, 1e-12);
  // A pavement's estimate widens as a cell's does.
  EXPECT_NEAR(out.pavements[0].crr.crr_sigma, 0.0005, 1e-12);
  EXPECT_DOUBLE_EQ(out.cells[0].crr, 0.0060);
  EXPECT_NEAR(out.cells[0].crr_hi - out.cells[0].crr, cfg.interval_z * 0.0005, 1e-12);
  EXPECT_TRUE(out.cells[0].identified) << out.cells[0].reason;
  EXPECT_NEAR(out.cells[1].crr_sigma, std::hypot(0.0005, 0.0008), 1e-12);
  EXPECT_FALSE(out.cells[1].identified);
  EXPECT_NE(out.cells[1].reason.find("its uncertainty 0.00094 exceeds the limit"), std::string::npos) << out.cells[1].reason;
  EXPECT_EQ(out.cells[2].samples, 0u);
  EXPECT_NEAR(out.trip.crr_sigma, std::hypot(0.0002, 0.0002), 1e-12);
  EXPECT_NEAR(out.trip.mass_sigma_kg, 1300.0, 1e-9);
  EXPECT_TRUE(out.trip.identified);
}

TEST(TorqueScaleConsider, ADriveThatFailsItsChecksStaysNotIdentified) {
  AnalyzerConfig cfg;
  TripResult t = good_trip(0.0055, 30000);
  t.wind_samples = 0;
  const DriveAnalysis out = widen_by_shift({{cell(0.0060, 0.0003)}, t, {}}, {{cell(0.0060, 0.0003)}, t, {}}, cfg);
  EXPECT_FALSE(out.trip.identified);
  EXPECT_FALSE(out.cells[0].identified);
  EXPECT_NE(out.cells[0].reason.find("no wind was measured"), std::string::npos) << out.cells[0].reason;
}

TEST(TorqueScaleConsider, TheSecondRunHoldsTheScaleOneSigmaOffAndTheFirstHoldsItExact) {
  AnalyzerConfig cfg;
  cfg.filter.truck.torque_scale_sigma = 0.04;
  cfg.filter.truck.cda_prior_m2 = 6.0;
  cfg.filter.truck.cda_per_torque_scale_m2 = 5.0;  // a calibrated CdA moves with the scale
  std::vector<double> sigmas, held, cda;
  analyse_with_torque_scale(cfg, [&](const AnalyzerConfig& c, TorqueScaleRun) {
    sigmas.push_back(c.filter.truck.torque_scale_sigma);
    held.push_back(c.filter.torque_scale_held);
    cda.push_back(c.filter.truck.cda_prior_m2);
    return DriveAnalysis{{}, good_trip(0.0055, 30000), {}};
  });
  ASSERT_EQ(sigmas.size(), 2u);
  EXPECT_EQ(sigmas[0], 0.0);
  EXPECT_EQ(sigmas[1], 0.0);
  EXPECT_EQ(held[0], 0.0);
  EXPECT_EQ(held[1], 0.04);
  EXPECT_EQ(cda[0], 6.0);
  EXPECT_DOUBLE_EQ(cda[1], 6.2);

  cfg.filter.truck.torque_scale_sigma = 0;
  int runs = 0;
  analyse_with_torque_scale(cfg, [&](const AnalyzerConfig&, TorqueScaleRun) {
    ++runs;
    return DriveAnalysis{};
  });
  EXPECT_EQ(runs, 1);
}

}  // namespace
}  // namespace roadload
