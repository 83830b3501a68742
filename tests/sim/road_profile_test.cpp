#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "roadload/sim/road_profile.hpp"
#include "welch.hpp"

namespace roadload::sim {
namespace {

struct LogLogFit {
  double level_at_n0;  // fitted G_d(0.1 cycle/m)
  double slope;        // the waviness, as -w
};

LogLogFit fit_loglog(const roadload::test::Psd& psd, double lo, double hi) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (std::size_t k = 1; k < psd.freq.size(); ++k) {
    if (psd.freq[k] < lo || psd.freq[k] > hi) continue;
    const double x = std::log(psd.freq[k] / 0.1);
    const double y = std::log(psd.density[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++count;
  }
  const double slope = (count * sxy - sx * sy) / (count * sxx - sx * sx);
  return {std::exp((sy - slope * sx) / count), slope};
}

double peak_frequency(const roadload::test::Psd& psd, double lo, double hi) {
  double best = 0, best_f = 0;
  for (std::size_t k = 0; k < psd.freq.size(); ++k) {
    if (psd.freq[k] >= lo && psd.freq[k] <= hi && psd.density[k] > best) {
      best = psd.density[k];
      best_f = psd.freq[k];
    }
  }
  return best_f;
}

std::vector<double> in_time(const RoadProfile& p, double speed_mps, double fs_hz) {
  std::vector<double> z;
  for (double t = 0; speed_mps * t <= p.end_m(); t += 1.0 / fs_hz) {
    z.push_back(p.enveloped_height_m(speed_mps * t));
  }
  return z;
}

TEST(Iso8608, ClassValuesAreTheGeometricMeans) {
  EXPECT_DOUBLE_EQ(iso8608_class_gd_m3('A'), 16e-6);
  EXPECT_DOUBLE_EQ(iso8608_class_gd_m3('C'), 256e-6);
  EXPECT_DOUBLE_EQ(iso8608_class_gd_m3('H'), 262144e-6);
  EXPECT_TRUE(std::isnan(iso8608_class_gd_m3('I')));
  EXPECT_TRUE(std::isnan(iso8608_class_gd_m3('a')));
}

// ISO 8608 law on 20 km: level at n0 within 10 % of the class value, waviness 2 +- 0.1.
TEST(Iso8608, RandomProfileHasTheClassPsd) {
  for (const char cls : {'A', 'C'}) {
    const double gd = iso8608_class_gd_m3(cls);
    const ProfileSegment seg{0.0, 20000.0, gd, {}};
    const auto p = RoadProfile::generate({&seg, 1}, 0.0, 20000.0, static_cast<std::uint64_t>(cls));
    const auto fit = fit_loglog(roadload::test::welch(p.raw_samples(), 1.0 / p.dx_m(), 4096), 0.05, 1.0);
    RecordProperty(std::string("class_X_level_ratio").replace(6, 1, 1, cls), std::to_string(fit.level_at_n0 / gd));
    RecordProperty(std::string("class_X_slope").replace(6, 1, 1, cls), std::to_string(fit.slope));
    EXPECT_NEAR(fit.level_at_n0 / gd, 1.0, 0.10) << cls;
    EXPECT_NEAR(fit.slope, -2.0, 0.1) << cls;
  }
}

// Gaps between segments keep the previous G_d; the slope noise scales with sqrt(G_d). The first
// difference of the profile is dx times the white slope: rms sqrt(G_s dx / 2).
TEST(RoadProfile, SegmentsScaleTheRoughnessAndGapsKeepThePreviousOne) {
  const ProfileSegment segs[] = {{0.0, 1000.0, 16e-6, {}}, {2000.0, 3000.0, 256e-6, {}}};
  const auto p = RoadProfile::generate(segs, 0.0, 3000.0, 5);
  const auto z = p.raw_samples();
  const auto rms_diff = [&](double from_m, double to_m) {
    double s = 0;
    int n = 0;
    const auto last = static_cast<std::size_t>(to_m / p.dx_m());
    for (auto i = static_cast<std::size_t>(from_m / p.dx_m()); i < last; ++i, ++n) {
      s += (z[i + 1] - z[i]) * (z[i + 1] - z[i]);
    }
    return std::sqrt(s / n);
  };
  const auto expected = [&](double gd) { return 2 * std::numbers::pi * 0.1 * std::sqrt(gd * p.dx_m() / 2); };
  EXPECT_NEAR(rms_diff(0, 1000) / expected(16e-6), 1.0, 0.03);
  EXPECT_NEAR(rms_diff(1000, 2000) / expected(16e-6), 1.0, 0.03);
  EXPECT_NEAR(rms_diff(2000, 3000) / expected(256e-6), 1.0, 0.03);
}

TEST(RoadProfile, SameSeedSameProfileOtherSeedOtherProfile) {
  const ProfileSegment seg{0.0, 2000.0, 64e-6, {4.572, 0.002, 0.0005}};
  const auto a = RoadProfile::generate({&seg, 1}, 0.0, 2000.0, 42);
  const auto b = RoadProfile::generate({&seg, 1}, 0.0, 2000.0, 42);
  const auto c = RoadProfile::generate({&seg, 1}, 0.0, 2000.0, 43);
  ASSERT_EQ(a.raw_samples().size(), 40001u);
  EXPECT_TRUE(std::ranges::equal(a.raw_samples(), b.raw_samples()));
  EXPECT_TRUE(std::ranges::equal(a.joint_positions_m(), b.joint_positions_m()));
  EXPECT_FALSE(std::ranges::equal(a.raw_samples(), c.raw_samples()));
  EXPECT_FALSE(std::ranges::equal(a.joint_positions_m(), c.joint_positions_m()));
}

// Joints draw from their own stream: rough + joints = rough alone + joints alone.
TEST(JointedConcrete, JointsDoNotChangeTheRandomProfile) {
  const ProfileSegment both{0.0, 1000.0, 64e-6, {4.572, 0.002, 0.0005}};
  const ProfileSegment rough{0.0, 1000.0, 64e-6, {}};
  const ProfileSegment joints{0.0, 1000.0, 0.0, {4.572, 0.002, 0.0005}};
  const auto pb = RoadProfile::generate({&both, 1}, 0.0, 1000.0, 9);
  const auto pr = RoadProfile::generate({&rough, 1}, 0.0, 1000.0, 9);
  const auto pj = RoadProfile::generate({&joints, 1}, 0.0, 1000.0, 9);
  for (std::size_t i = 0; i < pb.raw_samples().size(); ++i)
    ASSERT_NEAR(pb.raw_samples()[i], pr.raw_samples()[i] + pj.raw_samples()[i], 1e-15) << i;
}

// Jitter 0: each slab rises by the faulting and the next one starts that much lower, so the steps
// do not add up; curl lifts the slab edges.
TEST(JointedConcrete, SlabsAreASawtoothPlusCurl) {
  JointSpec spec{4.572, 0.002, 0.0, 0.01, 0.0, 0.0};
  const ProfileSegment seg{0.0, 1000.0, 0.0, spec};
  const auto p = RoadProfile::generate({&seg, 1}, 0.0, 1000.0, 1);
  const auto joints = p.joint_positions_m();
  ASSERT_EQ(joints.size(), 218u);  // floor(1000 / 4.572)
  const auto [lo, hi] = std::ranges::minmax(p.raw_samples());
  EXPECT_GE(lo, -0.001);
  EXPECT_LE(hi, 0.001);
  for (const double j : joints.subspan(0, joints.size() - 1)) {  // the last slab is shorter
    auto after = static_cast<std::size_t>(std::ceil(j / p.dx_m()));
    // A joint on the grid: the generator puts x >= j on the next slab.
    if (static_cast<double>(after - 1) * p.dx_m() >= j) --after;
    if (static_cast<double>(after) * p.dx_m() < j) ++after;
    const double step = p.raw_samples()[after] - p.raw_samples()[after - 1];
    ASSERT_NEAR(step, -0.002 * (1.0 - p.dx_m() / 4.572), 1e-12) << j;
  }
  spec = {4.572, 0.0, 0.0005, 0.01, 0.0, 0.0};
  const ProfileSegment curl{0.0, 1000.0, 0.0, spec};
  const auto pc = RoadProfile::generate({&curl, 1}, 0.0, 1000.0, 1);
  EXPECT_NEAR(pc.height_m(joints[10]), 0.0005, 3e-5);  // edges meet between samples
  EXPECT_NEAR(pc.height_m(joints[10] + 4.572 / 2), 0.0, 1e-7);
  EXPECT_NEAR(pc.height_m(joints[10] + 4.572 / 4), 0.0005 / 4, 1e-7);
}

// A sawcut narrower than the grid keeps its area, and joints stay within the jitter.
TEST(JointedConcrete, GapKeepsItsAreaAndJointsStayWithinTheJitter) {
  const ProfileSegment seg{0.0, 1000.0, 0.0, {8.5344, 0.0, 0.0, 0.01, 0.001, 0.1}};
  const auto p = RoadProfile::generate({&seg, 1}, 0.0, 1000.0, 3);
  const auto joints = p.joint_positions_m();
  ASSERT_EQ(joints.size(), 117u);
  double area = 0;
  for (const double z : p.raw_samples()) area += z * p.dx_m();
  EXPECT_NEAR(area, -117 * 0.01 * 0.001, 1e-12);
  for (std::size_t k = 0; k < joints.size(); ++k) EXPECT_NEAR(joints[k], static_cast<double>(k + 1) * 8.5344, 0.1);
}

// Parameter sheet, check 3: the joint line at V / L, within one PSD bin, in space and in time.
TEST(JointedConcrete, JointLinesAtSpacingAndSpeed) {
  struct Case {
    double spacing_m, speed_mps, line_hz;
  };
  for (const Case c : {Case{4.572, 13.4112, 2.933}, Case{8.5344, 24.587, 2.881}}) {
    const ProfileSegment seg{0.0, 10000.0, 0.0, {c.spacing_m, 0.002, 0.0005}};
    const auto p = RoadProfile::generate({&seg, 1}, 0.0, 10000.0, 7);
    const auto spatial = roadload::test::welch(p.raw_samples(), 1.0 / p.dx_m(), 4096);
    const double peak_n = peak_frequency(spatial, 0.05, 5.0);
    RecordProperty("line_cycles_per_m_" + std::to_string(c.spacing_m), std::to_string(peak_n));
    EXPECT_NEAR(peak_n, 1.0 / c.spacing_m, spatial.freq[1]) << c.spacing_m;

    constexpr double kFs_hz = 200.0;
    const auto temporal = roadload::test::welch(in_time(p, c.speed_mps, kFs_hz), kFs_hz, 8192);
    const double df = temporal.freq[1];
    const double line = peak_frequency(temporal, 0.5, 20.0);
    RecordProperty("line_hz_" + std::to_string(c.spacing_m), std::to_string(line));
    EXPECT_NEAR(line, c.line_hz, df) << c.spacing_m;
    EXPECT_NEAR(c.speed_mps / c.spacing_m, c.line_hz, 0.0005);
  }
}

// The footprint average: a wavelength of one footprint is gone, 5 m passes.
TEST(RoadProfile, EnvelopeRemovesFootprintWavelengthsKeepsLongOnes) {
  for (const double dx : {0.05, 0.01}) {
    for (const double wavelength : {0.2, 5.0}) {
      std::vector<double> z;
      for (double x = 0; x <= 100.0; x += dx) {
        z.push_back(0.001 * std::sin(2 * std::numbers::pi * x / wavelength + 0.3));
      }
      const auto p = RoadProfile::from_samples(z, 0.0, dx);
      double raw2 = 0, env2 = 0;
      for (double x = 10.0; x < 90.0; x += dx / 3) {  // off the grid too, away from the ends
        raw2 += p.height_m(x) * p.height_m(x);
        env2 += p.enveloped_height_m(x) * p.enveloped_height_m(x);
      }
      const double gain_db = 10 * std::log10(env2 / raw2);
      if (wavelength < 1.0) {
        EXPECT_LT(gain_db, -20.0) << dx;
      } else {
        EXPECT_GT(gain_db, -0.5) << dx;
      }
    }
  }
}

TEST(RoadProfile, EndsAndOutsideTakeTheNearestValue) {
  const ProfileSegment seg{0.0, 100.0, 256e-6, {}};
  const auto p = RoadProfile::generate({&seg, 1}, 10.0, 100.02, 2);
  EXPECT_DOUBLE_EQ(p.start_m(), 10.0);
  EXPECT_NEAR(p.end_m(), 100.05, 1e-9);
  EXPECT_EQ(p.raw_samples().front(), 0.0);
  EXPECT_EQ(p.height_m(-5.0), 0.0);
  EXPECT_EQ(p.height_m(1e6), p.raw_samples().back());
  EXPECT_NEAR(p.height_m(10.025), 0.5 * (p.raw_samples()[0] + p.raw_samples()[1]), 1e-15);
}

}  // namespace
}  // namespace roadload::sim
