// The response library on disk: what is read back is what was written, bit for bit; a library
// made for other inputs, cut short or altered is refused with the line and field; a stored drive
// of another speed or weather is judged by library_serves() as one in memory is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "roadload/gap/library_cache.hpp"
#include "roadload/gap/resimulate.hpp"
#include "roadload/gap/unseen.hpp"

namespace roadload::gap {
namespace {

class GapLibraryCache : public ::testing::Test {
 protected:
  void SetUp() override {
    auto s = sim::load_scenario("mnroad-mainline-30mph", ROADLOAD_CONFIG_DIR);
    ASSERT_TRUE(s) << s.error().to_string();
    run_.label = "drive-a";
    run_.model = s.value();
    run_.recorded.features.conditions.mean_speed_mps = s.value().speed_mps;
    lib_.scenarios = resimulations({run_});
    lib_.labels = {run_.label};
    lib_.layouts = {layout_for(run_.model.route)};
    const char* where[] = {"cell 1", "cell 2", "concrete 1-4 Hz"};
    for (int i = 0; i < 3; ++i) {
      lib_.keys.push_back(
          {run_.label, i == 2 ? "psd_db:tractor-front-axle-left" : "torque_nm", where[i], static_cast<std::uint8_t>(i % 2)});
      lib_.feature_half.push_back(static_cast<std::uint8_t>(i % 2));
    }
    lib_.baseline = Eigen::Vector3d(1.0 / 3.0, -2e-300, std::nan(""));
    lib_.sigma = Eigen::Vector3d(0.1, 1e300, 7.0);
    for (const sim::Effect effect : fitted_effects()) {
      const sim::EffectInfo& e = sim::effect_info(effect);
      lib_.responses.push_back({e.id, 0.0, e.max, e.min, lib_.baseline * 1.5, lib_.baseline * 0.5});
      lib_.null_gain.push_back(static_cast<double>(lib_.null_gain.size()) + 0.25);
    }
    lib_.priors = {nominal_priors(lib_.scenarios.front())};
    lib_.nominal_delta = Eigen::MatrixXd::Constant(3, static_cast<Eigen::Index>(lib_.priors.front().size()), 0.125);
    lib_.nominal_miss.assign(lib_.priors.front().size(), 1.5);
    lib_.null_chi2_mean = 431.7;
    lib_.null_chi2_sd = 29.1;
    lib_.null_chi2_count = 8;
  }

  RealRun run_;
  ModelLibrary lib_;
};

void expect_same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  ASSERT_EQ(a.size(), b.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (std::isnan(a(i))) {
      EXPECT_TRUE(std::isnan(b(i)));
    } else {
      EXPECT_EQ(a(i), b(i)) << i;
    }
  }
}

TEST_F(GapLibraryCache, ReadsBackEveryNumberExactlyUnderTheRunsOwnLabel) {
  RealRun other = run_;
  other.label = "drive-b";
  auto back = decode_library(encode_library(lib_, "0123456789abcdef"), "x.lib", "0123456789abcdef", {other});
  ASSERT_TRUE(back) << back.error().to_string();
  const ModelLibrary& b = back.value();
  ASSERT_EQ(b.keys.size(), 3u);
  EXPECT_EQ(b.keys[2].run, "drive-b");
  EXPECT_EQ(b.keys[2].where, "concrete 1-4 Hz");
  EXPECT_EQ(b.keys[1].half, 1);
  EXPECT_EQ(b.feature_half, lib_.feature_half);
  expect_same(b.baseline, lib_.baseline);
  expect_same(b.sigma, lib_.sigma);
  ASSERT_EQ(b.responses.size(), lib_.responses.size());
  for (std::size_t e = 0; e < b.responses.size(); ++e) {
    EXPECT_EQ(b.responses[e].effect, lib_.responses[e].effect);
    EXPECT_EQ(b.responses[e].m1, lib_.responses[e].m1);
    expect_same(b.responses[e].f2, lib_.responses[e].f2);
  }
  EXPECT_EQ(b.null_gain, lib_.null_gain);
  ASSERT_EQ(b.priors.front().size(), lib_.priors.front().size());
  EXPECT_EQ(b.priors.front()[1].id, lib_.priors.front()[1].id);
  EXPECT_EQ(b.priors.front()[1].sigma, lib_.priors.front()[1].sigma);
  EXPECT_EQ(b.nominal_delta, lib_.nominal_delta);
  EXPECT_EQ(b.nominal_miss, lib_.nominal_miss);
  EXPECT_EQ(b.null_chi2_mean, 431.7);
  EXPECT_EQ(b.null_chi2_count, 8u);
  EXPECT_TRUE(library_serves(b, resimulations({other})));
}

// A library of a program that still fitted an effect no feature sees is another program's.
TEST_F(GapLibraryCache, RefusesResponsesToAnEffectNoFeatureSees) {
  ASSERT_NE(unseen_by_features(sim::Effect::can_accel_offset), nullptr);
  for (const sim::Effect e : fitted_effects()) EXPECT_EQ(unseen_by_features(e), nullptr);
  EXPECT_EQ(fitted_effects().size() + 4, sim::effect_catalog().size());
  lib_.responses.insert(lib_.responses.begin(), {sim::Effect::wind_gusts, 0.0, 1.0, 2.0, lib_.baseline, lib_.baseline});
  lib_.null_gain.push_back(1.0);
  auto back = decode_library(encode_library(lib_, "f"), "x.lib", "f", {run_});
  ASSERT_FALSE(back);
  EXPECT_EQ(back.error().field, "response");
}

TEST_F(GapLibraryCache, TheStoredDriveDecidesWhomItServes) {
  lib_.scenarios.front().weather.pressure_pa += 2500.0;
  auto back = decode_library(encode_library(lib_, "f"), "x.lib", "f", {run_});
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_FALSE(library_serves(back.value(), resimulations({run_})));
  lib_.scenarios.front().weather.pressure_pa -= 1500.0;
  back = decode_library(encode_library(lib_, "f"), "x.lib", "f", {run_});
  EXPECT_TRUE(library_serves(back.value(), resimulations({run_})));
  lib_.scenarios.front().duration = Seconds{60.0};
  back = decode_library(encode_library(lib_, "f"), "x.lib", "f", {run_});
  EXPECT_FALSE(library_serves(back.value(), resimulations({run_})));
}

// The tire-warmup candidate's response is the library drive's warm-up: 10 minutes of driving
// leave 61 % of the cold excess, 30 minutes 22 %, 32 minutes 20 %.
TEST_F(GapLibraryCache, ALibraryServesDrivesWhoseTiresWereAsWarm) {
  lib_.scenarios.front().driven_before = Seconds{600.0};
  auto back = decode_library(encode_library(lib_, "f"), "x.lib", "f", {run_});
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back.value().scenarios.front().driven_before.count(), 600.0);
  EXPECT_FALSE(library_serves(back.value(), resimulations({run_})));
  lib_.scenarios.front().driven_before = Seconds{1920.0};
  EXPECT_TRUE(library_serves(lib_, resimulations({run_})));

  std::string text = encode_library(lib_, "f");
  const std::size_t drive = text.find("\ndrive\t");
  const std::size_t last = text.rfind('\t', text.find('\n', drive + 1));
  text.replace(last + 1, text.find('\n', last) - last - 1, "-1");
  auto bad = decode_library(text, "x.lib", "f", {run_});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().field, "drive");
  EXPECT_EQ(bad.error().line, 2);
}

TEST_F(GapLibraryCache, RefusesAnotherFingerprintACutFileAndAnAlteredNumber) {
  const std::string text = encode_library(lib_, "aaaa");
  auto wrong = decode_library(text, "x.lib", "bbbb", {run_});
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().line, 1);
  EXPECT_EQ(wrong.error().field, "fingerprint");

  auto cut = decode_library(text.substr(0, text.size() / 2), "x.lib", "aaaa", {run_});
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().file, "x.lib");
  EXPECT_GT(cut.error().line, 3);

  std::string altered = text;
  const std::size_t sigma = altered.find("\nsigma\t");
  altered.replace(altered.find('\t', sigma + 1) + 1, 1, "x");
  auto bad = decode_library(altered, "x.lib", "aaaa", {run_});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().field, "sigma");
  EXPECT_NE(bad.error().message.find("not a number"), std::string::npos) << bad.error().to_string();
}

TEST_F(GapLibraryCache, TheFingerprintFollowsTheTruckTheRoadAndTheRuleButNotTheWeather) {
  j1939::Database db;
  GapOptions o;
  std::vector<sim::Scenario> resims = resimulations({run_});
  const std::string base = library_fingerprint(resims, db, o);
  ASSERT_EQ(base.size(), 16u) << "the test program has no GNU build id";
  resims.front().weather.air_temp_c += 3.0;
  resims.front().speed_mps += 0.2;
  EXPECT_EQ(library_fingerprint(resims, db, o), base);
  resims.front().vehicle.cda_m2 *= 1.01;
  EXPECT_NE(library_fingerprint(resims, db, o), base);
  resims = resimulations({run_});
  resims.front().route.cells.front().crr += 1e-6;
  EXPECT_NE(library_fingerprint(resims, db, o), base);
  resims = resimulations({run_});
  o.noise_runs += 1;
  EXPECT_NE(library_fingerprint(resims, db, o), base);
}

// The tires' radius is one of the truck's nominal parameters when its vehicle file gives a
// spread: the model's truck is moved by the scenario's tire scale, which the ECUs do not know.
TEST_F(GapLibraryCache, TheTireRadiusIsANominalParameterOfTheModelsTruck) {
  sim::Scenario s = run_.model;
  const std::vector<NominalPrior> priors = nominal_priors(s);
  const auto radius = std::find_if(priors.begin(), priors.end(), [](const NominalPrior& p) { return p.id == Nominal::tire_radius; });
  ASSERT_NE(radius, priors.end());
  EXPECT_DOUBLE_EQ(radius->value, s.vehicle.drive_axle()->tire_radius_m);
  EXPECT_DOUBLE_EQ(radius->sigma, s.vehicle.tire_radius_sigma_m);
  set_nominal(s, Nominal::tire_radius, radius->value + 2 * radius->sigma);
  EXPECT_NEAR(s.tire_radius_scale, 1.0 + 2 * radius->sigma / radius->value, 1e-12);
  s.vehicle.tire_radius_sigma_m = 0;
  for (const NominalPrior& p : nominal_priors(s)) EXPECT_NE(p.id, Nominal::tire_radius) << "a radius nobody gave a spread for";
}

}  // namespace
}  // namespace roadload::gap
