// A route's grade from a survey and from GNSS heights of several passes in both directions, on a
// synthetic road of known elevation: the averaged grade is as close to the truth as the noise
// allows, its reported standard error is honest, more passes shrink it, and what cannot be used
// (fixes off the route or without a 3-D fix, bins with too few passes) is counted, not guessed.
#include "roadload/grade_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

namespace roadload {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLength_m = 3000.0;
// Every fix is projected on every segment: the checks of the statistics drive many passes over a
// road of one straight segment (its elevations unused: the truth is the function), the others
// over the same road surveyed every 20 m.
constexpr double kSurveySpacing_m = 20.0;
constexpr double kLon_deg = -93.70;
constexpr double kLat0_deg = 45.25;
constexpr double kMetresPerDegLat = 111136.7;  // meridian arc at 45.25 deg, so the road is 3000 m long
constexpr double kAntenna_m = 4.0;
constexpr double kRate_hz = 10.0;
constexpr double kSpeed_mps = 13.4;  // 30 mph, the report's closed-road Mainline runs

// Two swells of +-1.3 % grade each (the Mainline has +-0.5 %), wavelengths far above the 60 m base.
double true_elevation_m(double s_m) {
  return 262.0 + 3.0 * std::sin(2 * kPi * s_m / 1500.0) + 1.5 * std::sin(2 * kPi * s_m / 700.0 + 1.0);
}
double true_grade_rad(double s_m) {
  return std::atan(3.0 * 2 * kPi / 1500.0 * std::cos(2 * kPi * s_m / 1500.0) +
                   1.5 * 2 * kPi / 700.0 * std::cos(2 * kPi * s_m / 700.0 + 1.0));
}

// A straight road north along a meridian (a geodesic), surveyed every spacing_m with the true heights.
struct SyntheticRoute {
  std::vector<GeoPoint> points;
  std::vector<double> s_m;  // each point's distance along the built geometry
  RouteGeometry geometry;

  double lat_at_deg(double s) const {
    std::size_t i = 0;
    while (i + 2 < s_m.size() && s_m[i + 1] < s) ++i;
    const double w = (s - s_m[i]) / (s_m[i + 1] - s_m[i]);
    return points[i].lat_deg + w * (points[i + 1].lat_deg - points[i].lat_deg);
  }
};

SyntheticRoute make_route(double spacing_m = kSurveySpacing_m) {
  SyntheticRoute r;
  const auto n = static_cast<std::size_t>(std::llround(kLength_m / spacing_m)) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    r.points.push_back({kLat0_deg + static_cast<double>(i) * spacing_m / kMetresPerDegLat, kLon_deg, 0.0});
  }
  // Heights at the geometry's own distances, so the survey and the truth agree exactly.
  const RouteGeometry flat = *RouteGeometry::build(r.points);
  for (GeoPoint& p : r.points) {
    r.s_m.push_back(flat.project(p.lat_deg, p.lon_deg).s_m);
    p.elev_m = true_elevation_m(r.s_m.back());
  }
  r.geometry = *RouteGeometry::build(r.points);
  return r;
}

// The simulator's code-DGPS receiver (docs/simulator.md 5.3): vertical Gauss-Markov sigma 0.35 m,
// tau 100 s, plus white 0.2 m; horizontal white 0.2 m per axis.
struct Noise {
  double gm_sigma_m = 0.35;
  double gm_tau_s = 100.0;
  double white_sigma_m = 0.2;
  double horizontal_sigma_m = 0.2;
};

// One pass at constant speed from from_m to to_m (either way) at 10 Hz.
std::vector<GnssFix> drive(const SyntheticRoute& r, double from_m, double to_m, double speed_mps, const Noise& noise,
                           std::mt19937_64& rng) {
  std::normal_distribution<double> n01(0.0, 1.0);
  const double dt_s = 1.0 / kRate_hz;
  const double a = std::exp(-dt_s / noise.gm_tau_s);
  double gm_m = noise.gm_sigma_m * n01(rng);  // stationary from the start
  const double dir = to_m > from_m ? 1.0 : -1.0;
  std::vector<GnssFix> fixes;
  for (double s = from_m; dir * (to_m - s) >= 0; s += dir * speed_mps * dt_s) {
    gm_m = a * gm_m + noise.gm_sigma_m * std::sqrt(1 - a * a) * n01(rng);
    GnssFix f;
    f.lat_deg = r.lat_at_deg(s) + noise.horizontal_sigma_m * n01(rng) / kMetresPerDegLat;
    f.lon_deg = kLon_deg + noise.horizontal_sigma_m * n01(rng) / (111320.0 * std::cos(kLat0_deg * kPi / 180));
    f.alt_m = true_elevation_m(s) + kAntenna_m + gm_m + noise.white_sigma_m * n01(rng);
    f.mode = GnssFixMode::dgps;
    f.hdop = 0.9;
    fixes.push_back(f);
  }
  return fixes;
}

// `passes` whole-route passes, alternately northbound and southbound, one track each.
std::vector<std::vector<GnssFix>> drives(const SyntheticRoute& r, int passes, std::uint64_t seed, double speed_mps = kSpeed_mps,
                                         const Noise& noise = {}) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<GnssFix>> out;
  for (int p = 0; p < passes; ++p) {
    out.push_back(p % 2 == 0 ? drive(r, 0.5, kLength_m - 0.5, speed_mps, noise, rng)
                             : drive(r, kLength_m - 0.5, 0.5, speed_mps, noise, rng));
  }
  return out;
}

std::vector<GnssTrack> tracks_of(const std::vector<std::vector<GnssFix>>& d) {
  std::vector<GnssTrack> t;
  for (const auto& fixes : d) t.push_back({fixes, kAntenna_m});
  return t;
}

// The per-pass standard error of a +-L least-squares slope at speed v, from the noise model:
// white noise averaged over the fixes in each bin, then through the fit's weights; the
// Gauss-Markov part as a random walk (diffusion 2 sigma^2 / tau, since the window takes far
// less than tau) whose least-squares slope over a time T has variance 6 D / (5 T).
double predicted_pass_slope_sigma(const Noise& n, double speed_mps, const GradeConfig& cfg) {
  const double fixes_per_bin = cfg.bin_m / (speed_mps / kRate_hz);
  double sxx_m2 = 0;
  const int half = static_cast<int>(cfg.base_m / cfg.bin_m);
  for (int j = -half; j <= half; ++j) sxx_m2 += (j * cfg.bin_m) * (j * cfg.bin_m);
  const double white_var = n.white_sigma_m * n.white_sigma_m / fixes_per_bin / sxx_m2;
  const double diffusion_m2ps = 2 * n.gm_sigma_m * n.gm_sigma_m / n.gm_tau_s;
  const double window_s = 2 * cfg.base_m / speed_mps;
  const double walk_var = 6 * diffusion_m2ps / (5 * window_s) / (speed_mps * speed_mps);
  return std::sqrt(white_var + walk_var);
}

// Over the bins whose +-base window lies inside the route.
struct Errors {
  double rms_rad = 0;         // grade error against the truth
  double mean_sigma_rad = 0;  // reported standard error
  double normalized_rms = 0;  // error / reported sigma
  std::size_t bins = 0;
};

Errors errors_of(const GradeProfile& g) {
  Errors e;
  double se = 0, sn = 0, ss = 0;
  for (const GradeBin& b : g.bins()) {
    if (b.s_m < g.config().base_m || b.s_m > kLength_m - g.config().base_m) continue;
    const double err = b.grade_rad - true_grade_rad(b.s_m);
    se += err * err;
    sn += err * err / (b.grade_sigma_rad * b.grade_sigma_rad);
    ss += b.grade_sigma_rad;
    ++e.bins;
  }
  const auto n = static_cast<double>(e.bins);
  e.rms_rad = std::sqrt(se / n);
  e.mean_sigma_rad = ss / n;
  e.normalized_rms = std::sqrt(sn / n);
  return e;
}

GradeProfile gnss_profile(const SyntheticRoute& r, int passes, std::uint64_t seed, const GradeConfig& cfg = {}) {
  const auto d = drives(r, passes, seed);
  const auto t = tracks_of(d);
  return GradeProfile::from_gnss(r.geometry, t, cfg);
}

TEST(GradeSurvey, IsTheSurveysCentralDifferenceWithTheSurveysError) {
  const SyntheticRoute r = make_route();
  const double sigma_m = 0.02;
  const GradeProfile g = GradeProfile::from_survey(r.geometry, sigma_m);
  ASSERT_EQ(g.bins().size(), 300u);
  EXPECT_EQ(g.passes(), 0u);
  for (const GradeBin& b : g.bins()) {
    ASSERT_TRUE(std::isfinite(b.grade_rad)) << b.s_m;
    if (b.s_m < 30 || b.s_m > kLength_m - 30) continue;
    const double central = (r.geometry.elevation_m(b.s_m + 30) - r.geometry.elevation_m(b.s_m - 30)) / 60;
    EXPECT_NEAR(b.grade_rad, std::atan(central), 1e-12) << b.s_m;
    EXPECT_NEAR(b.grade_rad, true_grade_rad(b.s_m), 4e-4) << b.s_m;         // +-30 m smoothing, 20 m chords
    EXPECT_NEAR(b.grade_sigma_rad, std::sqrt(2.0) * sigma_m / 60.0, 1e-6);  // d atan = d slope / (1 + slope^2)
    EXPECT_DOUBLE_EQ(b.elevation_m, r.geometry.elevation_m(b.s_m));
  }
  // Between bin centres, linear; off the route, nothing.
  EXPECT_NEAR(g.grade_rad(1234.0), true_grade_rad(1234.0), 4e-4);
  EXPECT_NEAR(g.elevation_m(1234.0), true_elevation_m(1234.0), 0.01);
  EXPECT_TRUE(std::isnan(g.grade_rad(-1.0)));
  EXPECT_TRUE(std::isnan(g.grade_rad(kLength_m + 1.0)));
}

TEST(GradeGnss, AveragedGradeMatchesTheTruthWithinTheNoise) {
  const SyntheticRoute r = make_route();
  const Noise noise;
  const int passes = 8;
  const GradeProfile g = gnss_profile(r, passes, 11);
  EXPECT_EQ(g.passes(), 8u);
  EXPECT_EQ(g.fixes().off_route + g.fixes().no_3d_fix + g.fixes().beyond_ends + g.fixes().poor_hdop, 0u);
  const Errors e = errors_of(g);
  const double predicted_rad = predicted_pass_slope_sigma(noise, kSpeed_mps, g.config()) / std::sqrt(passes);
  std::printf("8 passes at 30 mph: grade RMS error %.4f %% over %zu bins, predicted %.4f %%, reported sigma %.4f %%\n",
              100 * e.rms_rad, e.bins, 100 * predicted_rad, 100 * e.mean_sigma_rad);
  // 1.5x: the bins are correlated over a window, so the RMS of ~50 independent windows scatters.
  EXPECT_LT(e.rms_rad, 1.5 * predicted_rad);
  EXPECT_GT(e.rms_rad, 0.5 * predicted_rad);  // else the noise model or the test is wrong
  // The height without the antenna: the passes' offsets average to within a few standard errors.
  for (const GradeBin& b : g.bins()) {
    ASSERT_EQ(b.elevation_passes, 8u);
    EXPECT_LT(std::abs(b.elevation_m - true_elevation_m(b.s_m)), 4 * b.elevation_sigma_m + 0.02) << b.s_m;
  }
}

TEST(GradeGnss, ReportedSigmaIsConsistentWithTheError) {
  const SyntheticRoute r = make_route(kLength_m);
  for (const int passes : {2, 3, 8}) {
    double sn = 0, n = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const Errors e = errors_of(gnss_profile(r, passes, seed * 100 + static_cast<std::uint64_t>(passes)));
      sn += e.normalized_rms * e.normalized_rms * static_cast<double>(e.bins);
      n += static_cast<double>(e.bins);
    }
    const double normalized_rms = std::sqrt(sn / n);
    std::printf("%d passes: RMS of error / reported sigma over 8 seeds: %.2f\n", passes, normalized_rms);
    EXPECT_GT(normalized_rms, 0.7) << passes;
    EXPECT_LT(normalized_rms, 1.4) << passes;
  }
}

TEST(GradeGnss, PoolingTheScatterKeepsTwoPassSigmasHonest) {
  // Two passes give each bin's slope variance one degree of freedom: a bin where they agree by
  // chance claims a grade it does not have (error / sigma heavy-tailed, Student t with 1 dof).
  const SyntheticRoute r = make_route(kLength_m);
  GradeConfig own;
  own.sigma_pool_m = 0;
  double pooled = 0, unpooled = 0, n = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto d = drives(r, 2, 70 + seed);
    const auto t = tracks_of(d);
    const Errors p = errors_of(GradeProfile::from_gnss(r.geometry, t));
    const Errors u = errors_of(GradeProfile::from_gnss(r.geometry, t, own));
    pooled += p.normalized_rms * p.normalized_rms * static_cast<double>(p.bins);
    unpooled += u.normalized_rms * u.normalized_rms * static_cast<double>(u.bins);
    n += static_cast<double>(p.bins);
  }
  std::printf("2 passes: RMS of error / sigma %.2f pooled over +-100 m, %.2f per bin\n", std::sqrt(pooled / n),
              std::sqrt(unpooled / n));
  EXPECT_LT(std::sqrt(pooled / n), 1.4);
  EXPECT_GT(std::sqrt(unpooled / n), 2.0);
}

TEST(GradeGnss, MorePassesShrinkTheSigma) {
  const SyntheticRoute r = make_route(kLength_m);
  const Errors four = errors_of(gnss_profile(r, 4, 21));
  const Errors sixteen = errors_of(gnss_profile(r, 16, 22));
  std::printf("4 passes: sigma %.4f %%, error %.4f %%; 16 passes: sigma %.4f %%, error %.4f %%\n", 100 * four.mean_sigma_rad,
              100 * four.rms_rad, 100 * sixteen.mean_sigma_rad, 100 * sixteen.rms_rad);
  // sqrt(16 / 4) = 2, give or take the scatter of a variance estimated from a few passes.
  EXPECT_GT(four.mean_sigma_rad / sixteen.mean_sigma_rad, 1.5);
  EXPECT_LT(four.mean_sigma_rad / sixteen.mean_sigma_rad, 2.7);
  EXPECT_LT(sixteen.rms_rad, four.rms_rad);
}

// The force balance carries a bin's grade error as a Gauss-Markov process along the road, its
// correlation length GradeProfile::error_correlation_m(): what a cell averages of it must be the
// error of the cell's mean grade, or the cell's CRR interval is too wide or too narrow.
TEST(GradeGnss, TheErrorsCorrelationGivesACellsMeanGradeItsError) {
  const SyntheticRoute r = make_route(kLength_m);
  constexpr double kCell_m = 500.0;
  double sn = 0, n = 0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const GradeProfile g = gnss_profile(r, 4, 300 + seed);
    const double l = g.error_correlation_m();
    const double share = 2 * l / kCell_m - 2 * l * l / (kCell_m * kCell_m) * (1 - std::exp(-kCell_m / l));
    for (double start = 100.0; start + kCell_m <= kLength_m - 100.0; start += kCell_m) {
      double err = 0, sigma = 0, bins = 0;
      for (const GradeBin& b : g.bins()) {
        if (b.s_m < start || b.s_m >= start + kCell_m) continue;
        err += b.grade_rad - true_grade_rad(b.s_m);
        sigma += b.grade_sigma_rad;
        ++bins;
      }
      const double z = (err / bins) / (sigma / bins * std::sqrt(share));
      sn += z * z;
      ++n;
    }
  }
  const double normalized_rms = std::sqrt(sn / n);
  std::printf("4 passes, %.0f cells of %.0f m: RMS of the mean grade's error over its sigma %.2f\n", n, kCell_m, normalized_rms);
  EXPECT_GT(normalized_rms, 0.75);
  EXPECT_LT(normalized_rms, 1.33);
}

TEST(GradeGnss, OffRouteFixesAreCountedAndIgnored) {
  const SyntheticRoute r = make_route(kLength_m);
  const auto clean = drives(r, 4, 31);
  auto dirty = clean;
  std::size_t added = 0;
  for (auto& fixes : dirty) {
    // Every 7th fix gets a twin on a parallel road 100 m east, 50 m higher.
    std::vector<GnssFix> with;
    for (std::size_t i = 0; i < fixes.size(); ++i) {
      with.push_back(fixes[i]);
      if (i % 7 != 0) continue;
      GnssFix other = fixes[i];
      other.lon_deg += 100.0 / (111320.0 * std::cos(kLat0_deg * kPi / 180));
      other.alt_m += 50.0;
      with.push_back(other);
      ++added;
    }
    fixes = with;
  }
  const GradeProfile a = GradeProfile::from_gnss(r.geometry, tracks_of(clean));
  const GradeProfile b = GradeProfile::from_gnss(r.geometry, tracks_of(dirty));
  EXPECT_EQ(b.fixes().off_route, added);
  EXPECT_EQ(b.fixes().used, a.fixes().used);
  EXPECT_EQ(b.passes(), a.passes());
  ASSERT_EQ(a.bins().size(), b.bins().size());
  for (std::size_t k = 0; k < a.bins().size(); ++k) {
    EXPECT_EQ(a.bins()[k].elevation_m, b.bins()[k].elevation_m);
    EXPECT_EQ(std::isfinite(a.bins()[k].grade_rad), std::isfinite(b.bins()[k].grade_rad));
    if (std::isfinite(a.bins()[k].grade_rad)) {
      EXPECT_EQ(a.bins()[k].grade_rad, b.bins()[k].grade_rad);
    }
  }
}

TEST(GradeGnss, FixesWithoutAHeightOrBeyondTheEndsAreCountedAndIgnored) {
  const SyntheticRoute r = make_route(kLength_m);
  std::mt19937_64 rng(41);
  auto out = drive(r, -200.0, kLength_m + 200.0, kSpeed_mps, {}, rng);  // runs in and out
  auto back = drive(r, kLength_m - 0.5, 0.5, kSpeed_mps, {}, rng);
  std::size_t flat = 0;
  for (std::size_t i = 0; i < back.size(); i += 10, ++flat) back[i].mode = GnssFixMode::fix_2d;
  back[5].hdop = 9.0;
  back[6].alt_m = std::nan("");
  const std::vector<GnssTrack> t = {{out, kAntenna_m}, {back, kAntenna_m}};
  const GradeProfile g = GradeProfile::from_gnss(r.geometry, t);
  EXPECT_EQ(g.fixes().no_3d_fix, flat + 1);
  EXPECT_EQ(g.fixes().poor_hdop, 1u);
  EXPECT_NEAR(static_cast<double>(g.fixes().beyond_ends), 400.0 / (kSpeed_mps / kRate_hz), 2.0);
  EXPECT_EQ(g.fixes().used + g.fixes().no_3d_fix + g.fixes().poor_hdop + g.fixes().beyond_ends + g.fixes().off_route,
            out.size() + back.size());
  EXPECT_EQ(g.passes(), 2u);
  EXPECT_EQ(g.bins_with_grade(), g.bins().size());  // a 2-D fix every second leaves every bin a fix
}

TEST(GradeGnss, BinsWithTooFewPassesHaveNoGrade) {
  const SyntheticRoute r = make_route(kLength_m);
  std::mt19937_64 rng(51);
  const auto whole = drive(r, 0.5, kLength_m - 0.5, kSpeed_mps, {}, rng);
  const auto half = drive(r, 1500.0, 0.5, kSpeed_mps, {}, rng);
  const std::vector<GnssTrack> t = {{whole, kAntenna_m}, {half, kAntenna_m}};
  const GradeProfile g = GradeProfile::from_gnss(r.geometry, t);
  for (const GradeBin& b : g.bins()) {
    if (b.s_m < 1500.0 - 40.0) {
      EXPECT_EQ(b.passes, 2u) << b.s_m;
      EXPECT_TRUE(std::isfinite(b.grade_rad)) << b.s_m;
      EXPECT_TRUE(std::isfinite(b.grade_sigma_rad)) << b.s_m;
    } else if (b.s_m > 1500.0 + 40.0) {
      EXPECT_EQ(b.passes, 1u) << b.s_m;
      EXPECT_EQ(b.elevation_passes, 1u) << b.s_m;
      EXPECT_TRUE(std::isnan(b.grade_rad)) << b.s_m;
      EXPECT_TRUE(std::isnan(b.grade_sigma_rad)) << b.s_m;
      EXPECT_TRUE(std::isnan(b.elevation_sigma_m)) << b.s_m;
      EXPECT_TRUE(std::isfinite(b.elevation_m)) << b.s_m;  // measured once: a height, no error bar
    }
  }
  EXPECT_TRUE(std::isnan(g.grade_rad(2500.0)));
  EXPECT_TRUE(std::isfinite(g.grade_rad(700.0)));
  GradeConfig three;
  three.min_passes = 3;
  EXPECT_EQ(GradeProfile::from_gnss(r.geometry, t, three).bins_with_grade(), 0u);
}

TEST(GradeGnss, ARoundTripInOneRecordingIsTwoPasses) {
  const SyntheticRoute r = make_route();
  std::mt19937_64 rng(61);
  auto trip = drive(r, 0.5, kLength_m - 0.5, kSpeed_mps, {}, rng);
  const auto back = drive(r, kLength_m - 0.5, 0.5, kSpeed_mps, {}, rng);
  trip.insert(trip.end(), back.begin(), back.end());
  const std::vector<GnssTrack> t = {{trip, kAntenna_m}};
  const GradeProfile g = GradeProfile::from_gnss(r.geometry, t);
  EXPECT_EQ(g.passes(), 2u);
  EXPECT_EQ(g.bins_with_grade(), g.bins().size());
  for (const GradeBin& b : g.bins()) EXPECT_EQ(b.elevation_passes, 2u) << b.s_m;
}

}  // namespace
}  // namespace roadload
