// The CRR filter on drives generated from its own model with known truth: it converges, its
// uncertainty is honest (NEES and NIS in their 95 % bands), it needs no heap per step, rejects
// outliers, drops stale data, says when CRR is not identifiable, and its smoother beats it offline.
#include "roadload/crr_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "allocation_counter.hpp"
#include "roadload/drive_analyzer.hpp"
#include "vehicles.hpp"

namespace roadload {
namespace {

using namespace std::chrono_literals;

constexpr double kDt = 0.1;
constexpr double kSpeedSigma = 0.03;
constexpr double kRippleCorrelation_m = 120.0;

// A truck driven by the filter's own force balance with white force noise: the reference for
// consistency. Speed alternates between two cruise speeds so CRR and CdA separate.
struct Drive {
  std::vector<model::ForceInputs> inputs;
  std::vector<double> speed_meas;
  std::vector<double> crr_true;
};

Drive make_drive(std::uint64_t seed, double seconds, double crr, double cda, const CrrFilterConfig& cfg, bool vary_speed = true,
                 double crr_step_at_s = -1, double crr_after = 0, double torque_bias_nm = 0, double ripple_sigma_mps = 0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const model::TruckModel& tm = cfg.truck;
  const double m_eff = model::effective_mass_kg(tm, 0.73);
  const double gain = model::wheel_force_per_flywheel_nm(tm, 0.73);
  const double weight = tm.mass_kg * model::kGravity_mps2;
  Drive d;
  double v = 20.0, ripple = 0, offset = 0;
  const auto steps = static_cast<std::size_t>(seconds / kDt);
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) * kDt;
    const double c = crr_step_at_s >= 0 && t >= crr_step_at_s ? crr_after : crr;
    const double target = vary_speed ? (std::fmod(t, 240.0) < 120.0 ? 15.0 : 27.0) : 20.0;
    const double rho = 1.18, wind = 2.0, grade = 0.01 * std::sin(t / 60.0);
    const double aero = 0.5 * rho * cda * (v + wind) * std::abs(v + wind);
    const double resist = aero + weight * std::sin(grade) + c * weight * std::cos(grade);
    const double tractive = resist + m_eff * 0.3 * (target - v);
    model::ForceInputs in;
    in.t = capture_time_from_ns(static_cast<std::int64_t>(std::llround((t + kDt) * 1e9)));
    in.tractive_n = tractive;
    in.air_density_kgpm3 = rho;
    in.headwind_mps = wind;
    in.grade_rad = grade;
    in.effective_mass_kg = m_eff;
    in.wheel_force_per_flywheel_nm = gain;
    in.usable = true;
    in.ripple_sigma_mps = ripple_sigma_mps;
    in.ripple_correlation_m = kRippleCorrelation_m;
    // The white force noise the filter assumes: a floor and a share of the aero drag.
    const double w = std::hypot(cfg.force_noise_n, cfg.aero_force_noise_per_sqrt_hz * aero) * std::sqrt(1.0 / kDt) * n01(rng);
    // The signals understate the flywheel torque by the bias the filter only considers.
    v += kDt * (tractive + gain * torque_bias_nm - resist + w) / m_eff;
    d.inputs.push_back(in);
    // A rough road's ripple: the speed its heights lend and take back, correlated along the road.
    const double phi = std::exp(-v * kDt / kRippleCorrelation_m);
    ripple = phi * ripple + ripple_sigma_mps * std::sqrt(1.0 - phi * phi) * n01(rng);
    // The force errors that integrate to nothing: a speed offset correlated in time.
    const double tau = cfg.bounded_force_correlation.count(), phi_b = std::exp(-kDt / tau);
    const double bounded_mps = cfg.bounded_aero_force_noise_per_sqrt_hz * aero / m_eff * std::sqrt(tau / 2.0);
    offset = phi_b * offset + bounded_mps * std::sqrt(1.0 - phi_b * phi_b) * n01(rng);
    d.speed_meas.push_back(v + ripple + offset + kSpeedSigma * n01(rng));
    d.crr_true.push_back(c);
  }
  return d;
}

// Runs a fresh filter over a drive; returns it at the end.
CrrFilter run(const CrrFilterConfig& cfg, const Drive& d) {
  CrrFilter f(cfg);
  f.start(capture_time_from_ns(0), d.speed_meas[0]);
  for (std::size_t k = 0; k < d.inputs.size(); ++k) {
    f.predict_to(d.inputs[k]);
    f.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
  }
  return f;
}

// The MnROAD truck as the analyzer takes it.
CrrFilterConfig config() {
  CrrFilterConfig cfg = analyzer_config(shipped::mnroad_vehicle()).filter;
  cfg.crr_walk_per_sqrt_s = 1e-9;  // the truth here is constant
  cfg.cda_walk_per_sqrt_s = 1e-9;
  // These drives' truck is the model's exactly: no tractive or mass scale error to consider (their
  // own test below gives the drive one).
  cfg.truck.torque_scale_sigma = 0;
  cfg.truck.efficiency_scale_sigma = 0;
  cfg.truck.mass_sigma_kg = 0;
  return cfg;
}

TEST(CrrFilter, ConvergesToTheTrueCrrAndCdaWhenSpeedVaries) {
  const CrrFilterConfig cfg = config();
  const CrrFilter f = run(cfg, make_drive(1, 1200, 0.0061, 5.8, cfg));
  EXPECT_NEAR(f.crr(), 0.0061, 3 * f.crr_sigma());
  EXPECT_LT(f.crr_sigma(), 0.0002);
  EXPECT_NEAR(f.cda_m2(), 5.8, 3 * std::sqrt(f.core().p()(CrrState::cda, CrrState::cda)));
  EXPECT_TRUE(f.crr_identified());
  // The gate rejects 1e-4 of consistent updates: 1.2 of these 12,000 on average.
  EXPECT_LE(f.counters().outliers, 5u);
  EXPECT_NEAR(f.counters().mean_nis(), 1.0, 0.05);
}

TEST(CrrFilter, NeesAndNisLieInTheir95PercentBandsWithATorqueBiasOnlyConsidered) {
  const CrrFilterConfig cfg = config();
  constexpr int kRuns = 50;
  std::mt19937_64 rng(99);
  std::normal_distribution<double> bias(0.0, cfg.torque_bias_sigma_nm);
  double nees_sum = 0, nis_sum = 0;
  std::size_t nis_n = 0;
  for (int run = 0; run < kRuns; ++run) {
    const Drive d = make_drive(100 + static_cast<std::uint64_t>(run), 600, 0.0055, 6.2 + 0.6 * std::sin(run), cfg, true, -1, 0,
                               bias(rng));
    CrrFilter f(cfg);
    f.start(capture_time_from_ns(0), d.speed_meas[0]);
    for (std::size_t k = 0; k < d.inputs.size(); ++k) {
      f.predict_to(d.inputs[k]);
      const auto r = f.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
      if (k > 50) {
        nis_sum += r.nis;
        ++nis_n;
      }
    }
    // NEES of [CRR, CdA] at the end of the run.
    Eigen::Vector2d e(f.crr() - 0.0055, f.cda_m2() - (6.2 + 0.6 * std::sin(run)));
    Eigen::Matrix2d p = f.core().p().block<2, 2>(CrrState::crr, CrrState::crr);
    nees_sum += e.dot(p.ldlt().solve(e));
  }
  // Sum of 50 chi-square(2) is chi-square(100): 95 % band [74.2, 129.6].
  EXPECT_GT(nees_sum, 74.2);
  EXPECT_LT(nees_sum, 129.6);
  // Mean NIS of ~300,000 one-dimensional innovations: 1 within a few per mille; allow 3 %.
  EXPECT_NEAR(nis_sum / static_cast<double>(nis_n), 1.0, 0.03);
}

// A rough road's speed ripple, bounded, is its own state: with it the innovations and CRR's error
// are what the filter states; a filter told of no ripple reads it as force, and NIS is far above 1.
TEST(CrrFilter, ARoughRoadsSpeedRippleIsItsOwnStateNotForce) {
  const CrrFilterConfig cfg = config();
  constexpr int kRuns = 20;
  constexpr double kRipple = 0.06;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> bias(0.0, cfg.torque_bias_sigma_nm);
  double nees = 0, nis_told = 0, nis_untold = 0;
  std::size_t n = 0;
  for (int run = 0; run < kRuns; ++run) {
    const Drive d = make_drive(300 + static_cast<std::uint64_t>(run), 600, 0.0055, 6.2, cfg, true, -1, 0, bias(rng), kRipple);
    CrrFilter told(cfg), untold(cfg);
    told.start(capture_time_from_ns(0), d.speed_meas[0]);
    untold.start(capture_time_from_ns(0), d.speed_meas[0]);
    for (std::size_t k = 0; k < d.inputs.size(); ++k) {
      model::ForceInputs smooth = d.inputs[k];
      smooth.ripple_sigma_mps = 0;
      told.predict_to(d.inputs[k]);
      untold.predict_to(smooth);
      const auto a = told.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
      const auto b = untold.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
      if (k > 50) {
        nis_told += a.nis;
        nis_untold += b.nis;
        ++n;
      }
    }
    nees += (told.crr() - 0.0055) * (told.crr() - 0.0055) / (told.crr_sigma() * told.crr_sigma());
  }
  // Sum of 20 chi-square(1) is chi-square(20): 95 % band [9.59, 34.17].
  EXPECT_GT(nees, 9.59);
  EXPECT_LT(nees, 34.17);
  EXPECT_NEAR(nis_told / static_cast<double>(n), 1.0, 0.05);
  EXPECT_GT(nis_untold / static_cast<double>(n), 1.5);
}

// A CdA calibrated from two speeds took up the engine-loss map's torque bias b: its error is k b
// plus its own scatter. At one later speed the two add up in CRR; the filter's interval holds them
// only with their correlation in its prior.
TEST(CrrFilter, ACalibratedCdasCorrelationWithTheTorqueBiasKeepsNeesInItsBand) {
  constexpr int kRuns = 100;
  constexpr double kPerNm = 0.02, kScatter = 0.01, kTrueCda = 6.2;
  CrrFilterConfig cfg = config();
  cfg.estimate_cda = false;
  cfg.torque_bias_sigma_nm = 5.0;
  cfg.truck.cda_sigma_m2 = std::hypot(kScatter, kPerNm * cfg.torque_bias_sigma_nm);
  const double rho = -kPerNm * cfg.torque_bias_sigma_nm / cfg.truck.cda_sigma_m2;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> n01(0.0, 1.0);
  double nees = 0, nees_uncorrelated = 0;
  for (int n = 0; n < kRuns; ++n) {
    const double bias_nm = cfg.torque_bias_sigma_nm * n01(rng);
    const Drive d = make_drive(300 + static_cast<std::uint64_t>(n), 300, 0.0055, kTrueCda, cfg, false, -1, 0, bias_nm);
    CrrFilterConfig fitted = cfg;
    fitted.truck.cda_prior_m2 = kTrueCda + kPerNm * bias_nm + kScatter * n01(rng);
    for (const double correlation : {rho, 0.0}) {
      fitted.truck.cda_torque_bias_correlation = correlation;
      const CrrFilter f = run(fitted, d);
      const double e = f.crr() - 0.0055;
      (correlation == 0.0 ? nees_uncorrelated : nees) += e * e / (f.crr_sigma() * f.crr_sigma());
    }
  }
  // chi-square(100): 95 % band [74.2, 129.6]. Without the correlation the interval is too narrow.
  std::printf("NEES over %d drives: %.1f with the correlation, %.1f without\n", kRuns, nees, nees_uncorrelated);
  EXPECT_GT(nees, 74.2);
  EXPECT_LT(nees, 129.6);
  EXPECT_GT(nees_uncorrelated, 129.6);
}

TEST(CrrFilter, AStepIsFreeOfHeapAllocations) {
  const CrrFilterConfig cfg = config();
  const Drive d = make_drive(2, 60, 0.0055, 6.2, cfg);
  CrrFilter f(cfg);
  f.start(capture_time_from_ns(0), d.speed_meas[0]);
  std::size_t allocations = 0;
  {
    const test::CountAllocations count;
    for (std::size_t k = 0; k < d.inputs.size(); ++k) {
      f.predict_to(d.inputs[k]);
      f.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
    }
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(f.counters().predicts, d.inputs.size());
}

TEST(CrrFilter, CovarianceStaysSymmetricPositiveSemiDefiniteUnderTinyMeasurementNoise) {
  CrrFilterConfig cfg = config();
  const Drive d = make_drive(3, 3000, 0.0055, 6.2, cfg);
  CrrFilter f(cfg);
  f.start(capture_time_from_ns(0), d.speed_meas[0]);
  for (std::size_t k = 0; k < d.inputs.size(); ++k) {
    f.predict_to(d.inputs[k]);
    f.update_speed(d.inputs[k].t, d.speed_meas[k], 1e-6);  // near-singular S: the Joseph form's case
  }
  const auto& p = f.core().p();
  EXPECT_LT((p - p.transpose()).norm(), 1e-18);
  // Semi-definite: the grade error has no variance on a road whose grade is exact. By Sylvester's
  // law of inertia the pivoted LDLT's D has as many negative entries as P has negative eigenvalues.
  const Eigen::LDLT<CrrFilter::Mat> ldlt(p);
  EXPECT_GE(ldlt.vectorD().minCoeff(), -1e-15 * ldlt.vectorD().maxCoeff());
  EXPECT_GT(p(CrrState::crr, CrrState::crr), 0.0);
}

TEST(CrrFilter, OutliersAreGatedAndStaleSpeedsDropped) {
  const CrrFilterConfig cfg = config();
  const Drive d = make_drive(4, 120, 0.0055, 6.2, cfg);
  CrrFilter f(cfg);
  f.start(capture_time_from_ns(0), d.speed_meas[0]);
  for (std::size_t k = 0; k < d.inputs.size(); ++k) {
    f.predict_to(d.inputs[k]);
    const double z = k == 500 ? d.speed_meas[k] + 5.0 : d.speed_meas[k];
    const auto r = f.update_speed(d.inputs[k].t, z, kSpeedSigma);
    if (k == 500) {
      EXPECT_FALSE(r.accepted);
    }
  }
  // Beyond the injected one, genuine chi-square tails: 1,200 updates at 1e-4 expect 0.12.
  EXPECT_GE(f.counters().outliers, 1u);
  EXPECT_LE(f.counters().outliers, 3u);
  // 200 ms late: used with its lag in the uncertainty; 2 s late: dropped and counted.
  EXPECT_TRUE(f.update_speed(f.time() - 200ms, f.speed_mps(), kSpeedSigma).accepted);
  EXPECT_FALSE(f.update_speed(f.time() - 2s, f.speed_mps(), kSpeedSigma).accepted);
  EXPECT_EQ(f.counters().late_used, 1u);
  EXPECT_EQ(f.counters().late_dropped, 1u);
}

TEST(CrrFilter, SaysCrrIsNotIdentifiedAtOneSpeedWithoutAnAeroPrior) {
  CrrFilterConfig cfg = config();
  cfg.truck.cda_sigma_m2 = 5.0;  // no useful prior on the aero drag
  const CrrFilter steady = run(cfg, make_drive(5, 600, 0.0055, 6.2, cfg, false));
  EXPECT_FALSE(steady.crr_identified()) << "CRR sigma " << steady.crr_sigma();
  const CrrFilter varied = run(cfg, make_drive(5, 1200, 0.0055, 6.2, cfg, true));
  EXPECT_TRUE(varied.crr_identified()) << "CRR sigma " << varied.crr_sigma();
}

TEST(CrrFilter, SmootherTracksAPavementChangeBetterThanTheFilter) {
  CrrFilterConfig cfg = config();
  cfg.crr_walk_per_sqrt_s = 1e-4;  // pavements change
  const Drive d = make_drive(6, 900, 0.0050, 6.2, cfg, true, 450.0, 0.0065);
  CrrFilter f(cfg);
  ekf::RtsSmoother<CrrState::count> smoother;
  f.attach(&smoother);
  f.start(capture_time_from_ns(0), d.speed_meas[0]);
  std::vector<double> filtered;
  for (std::size_t k = 0; k < d.inputs.size(); ++k) {
    f.predict_to(d.inputs[k]);
    f.update_speed(d.inputs[k].t, d.speed_meas[k], kSpeedSigma);
    filtered.push_back(f.crr());
  }
  smoother.finish(f.core().x(), f.core().p());
  smoother.smooth();
  ASSERT_EQ(smoother.size(), d.inputs.size());
  double se_f = 0, se_s = 0;
  for (std::size_t k = 1; k < d.inputs.size(); ++k) {
    se_f += std::pow(filtered[k - 1] - d.crr_true[k - 1], 2);
    se_s += std::pow(smoother.x(k)(CrrState::crr) - d.crr_true[k - 1], 2);
  }
  EXPECT_LT(se_s, 0.7 * se_f) << "filtered RMSE " << std::sqrt(se_f / 9000) << ", smoothed " << std::sqrt(se_s / 9000);
}

// A truck whose tractive force is 5 % below what its ECU's torque and its file's efficiency say
// (a 3 % torque scale and 1.6 % of efficiency are one sigma each): a filter that takes them as exact
// puts the missing force on CRR, confidently wrong. With the scale considered its interval holds the
// truth: here the grade's swings (+-1 %) move the tractive force and with it the scale's share, which
// CRR's constant force does not, so the considered filter's estimate itself lands near the truth.
TEST(CrrFilter, ATractiveScaleConsideredKeepsTheTruthInItsInterval) {
  CrrFilterConfig exact = config();
  exact.truck.cda_sigma_m2 = 1e-6;  // the scale alone, not hidden behind CdA's prior
  Drive d = make_drive(7, 900, 0.0055, exact.truck.cda_prior_m2, exact, false);
  for (model::ForceInputs& in : d.inputs) in.tractive_n *= 1.05;
  const CrrFilter taken_as_exact = run(exact, d);
  CrrFilterConfig considered = exact;
  // This drive states no indicated torque: the whole scale is carried as the efficiency's.
  considered.truck.efficiency_scale_sigma = std::hypot(0.03, 0.015 / 0.94);
  const CrrFilter f = run(considered, d);
  std::printf("CRR error %.5f (as exact %.5f); sigma taken as exact %.5f, with the scale considered %.5f\n", f.crr() - 0.0055,
              taken_as_exact.crr() - 0.0055, taken_as_exact.crr_sigma(), f.crr_sigma());
  EXPECT_GT(std::abs(taken_as_exact.crr() - 0.0055), 3 * taken_as_exact.crr_sigma());
  EXPECT_LT(std::abs(f.crr() - 0.0055), 2.58 * f.crr_sigma());
}

TEST(CrrFilter, HillsTellTheMassFromTheCrr) {
  // A truck 6 % heavier than declared over +-1 % grades: the grade's force swings with the mass,
  // the rolling resistance's hardly, so the filter finds the mass and keeps CRR in its interval.
  CrrFilterConfig heavy = config();
  heavy.truck.mass_kg *= 1.06;
  Drive d = make_drive(11, 1800, 0.0055, heavy.truck.cda_prior_m2, heavy, false);
  CrrFilterConfig cfg = config();
  cfg.truck.mass_sigma_kg = 0.05 * cfg.truck.mass_kg;
  // The signals tell the rotating parts' inertia, not the cargo's.
  for (model::ForceInputs& in : d.inputs) in.effective_mass_kg -= heavy.truck.mass_kg - cfg.truck.mass_kg;
  const CrrFilter f = run(cfg, d);
  std::printf("mass %.0f +- %.0f kg (truth %.0f, prior %.0f +- %.0f); CRR error %.5f +- %.5f\n", f.mass_kg(), f.mass_sigma_kg(),
              heavy.truck.mass_kg, cfg.truck.mass_kg, cfg.truck.mass_sigma_kg, f.crr() - 0.0055, f.crr_sigma());
  EXPECT_NEAR(f.mass_kg(), heavy.truck.mass_kg, 2.58 * f.mass_sigma_kg());
  EXPECT_LT(f.mass_sigma_kg(), 0.5 * cfg.truck.mass_sigma_kg);
  EXPECT_LT(std::abs(f.crr() - 0.0055), 2.58 * f.crr_sigma());
}

}  // namespace
}  // namespace roadload
