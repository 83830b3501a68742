// The network's REML fit on data drawn from its own model: sections' CRR inside their intervals
// about as often as 90 % intervals should be, variance components recovered.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadload/network/minimize.hpp"
#include "roadload/network/mixed_model.hpp"

namespace roadload::network {
namespace {

struct Drawn {
  MixedModel model;
  std::vector<double> section_crr;
};

// Sections' CRR, trucks' offsets and drives' shared errors, each drive over 12 of the sections.
Drawn draw(std::uint32_t seed, double truck_sd, double drive_sd, double residual_sd) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0048, 0.0064);
  constexpr std::size_t kSections = 40, kTrucks = 20, kDrivesPerTruck = 6, kPerDrive = 12;
  Drawn d;
  for (std::size_t s = 0; s < kSections; ++s) d.section_crr.push_back(uniform(rng));
  d.model.fixed_columns = kSections;
  d.model.terms = {{"truck", kTrucks}, {"drive", kTrucks * kDrivesPerTruck}};
  for (std::size_t t = 0; t < kTrucks; ++t) {
    const double truck = truck_sd * normal(rng);
    for (std::size_t k = 0; k < kDrivesPerTruck; ++k) {
      const std::size_t drive = t * kDrivesPerTruck + k;
      const double shared = drive_sd * normal(rng);
      const std::size_t first = (drive * 7) % kSections;
      for (std::size_t j = 0; j < kPerDrive; ++j) {
        const std::size_t s = (first + j) % kSections;
        MixedModel::Observation o;
        o.y = d.section_crr[s] + truck + shared + residual_sd * normal(rng);
        o.fixed = {{s, 1.0}};
        o.random = {{d.model.random_index(0, t), 1.0}, {d.model.random_index(1, drive), 1.0}};
        d.model.observations.push_back(o);
      }
    }
  }
  return d;
}

TEST(MixedModel, RecoversSectionsAndVariances) {
  int inside = 0, total = 0, truck_inside = 0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const Drawn d = draw(seed, 3e-4, 2e-4, 1e-4);
    const MixedModelFit fit = fit_reml(d.model);
    ASSERT_TRUE(fit.converged);
    ASSERT_EQ(fit.terms.size(), 2u);
    EXPECT_NEAR(fit.residual.sd, 1e-4, 0.15e-4);
    EXPECT_NEAR(fit.terms[1].sd, 2e-4, 0.6e-4);
    truck_inside += fit.terms[0].sd_lo <= 3e-4 && 3e-4 <= fit.terms[0].sd_hi;
    for (std::size_t s = 0; s < d.section_crr.size(); ++s) {
      const double sd = std::sqrt(fit.fixed_cov(s, s));
      inside += std::abs(fit.fixed(s) - d.section_crr[s]) <= 1.645 * sd;
      ++total;
    }
  }
  // 200 sections, but 5 draws of a shared truck mean: wide bounds around 90 %.
  EXPECT_GE(inside, 0.75 * total);
  EXPECT_LE(inside, 0.99 * total);
  EXPECT_GE(truck_inside, 3);
}

TEST(MixedModel, AbsentVarianceRunsToZero) {
  const Drawn d = draw(7, 0.0, 2e-4, 1e-4);
  const MixedModelFit fit = fit_reml(d.model);
  ASSERT_TRUE(fit.converged);
  EXPECT_LT(fit.terms[0].sd, 1e-4);
  EXPECT_LT(fit.terms[0].sd_lo, 0.5e-4);
}

TEST(MixedModel, TooFewObservationsIsNoFit) {
  MixedModel m;
  m.fixed_columns = 2;
  m.observations.push_back({0.005, 1, {{0, 1.0}}, {}});
  const MixedModelFit fit = fit_reml(m);
  EXPECT_FALSE(fit.converged);
  EXPECT_TRUE(std::isnan(fit.fixed(0)));
}

TEST(Minimize, FindsAQuadraticsMinimum) {
  const Minimum m = minimize([](const std::vector<double>& x) { return (x[0] - 1) * (x[0] - 1) + 3 * (x[1] + 2) * (x[1] + 2); },
                             {0, 0}, 1.0);
  EXPECT_TRUE(m.converged);
  EXPECT_NEAR(m.x[0], 1, 1e-3);
  EXPECT_NEAR(m.x[1], -2, 1e-3);
}

}  // namespace
}  // namespace roadload::network
