// The nominal calibration on synthetic whitened residuals: another truck than the model's is
// fitted as such, and is not taken for an unmodelled effect.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadload/gap/diagnosis.hpp"

namespace roadload::gap {
namespace {

constexpr Eigen::Index kFeatures = 400;

Eigen::VectorXd shape(double freq, double phase) {
  Eigen::VectorXd v(kFeatures);
  for (Eigen::Index i = 0; i < kFeatures; ++i) v(i) = std::sin(freq * static_cast<double>(i / 2) + phase);
  return v;
}

struct Truck {
  Problem problem;
  std::mt19937_64 rng{7};

  Truck() {
    for (Eigen::Index i = 0; i < kFeatures; ++i) {
      problem.keys.push_back({"run", "torque_nm", "cell " + std::to_string(i / 2), static_cast<std::uint8_t>(i % 2)});
    }
    // Two nominal parameters (responses of 3 and 2 noise sigmas per prior sigma) and three
    // candidates, the first of which moves the features exactly as the first parameter does.
    problem.nominal.push_back({"CdA", "m2", 6.2, 0.6, 3.0 * shape(0.05, 0.3)});
    problem.nominal.push_back({"mass", "kg", 36000, 360, 2.0 * shape(0.011, 1.1)});
    const Eigen::VectorXd effect_shapes[] = {shape(0.05, 0.3), shape(0.031, 2.0), shape(0.083, 0.7)};
    for (std::size_t c = 0; c < 3; ++c) {
      problem.candidates.push_back(Candidate::from_two("effect-" + std::to_string(c), "unit", 0.0, 0.0, 3.0, 1.0,
                                                       2.0 * effect_shapes[c], 2.0, 4.0 * effect_shapes[c]));
    }
    problem.z = Eigen::VectorXd::Zero(kFeatures);
  }
  void add_noise() {
    std::normal_distribution<double> normal;
    for (Eigen::Index i = 0; i < kFeatures; ++i) problem.z(i) += normal(rng);
  }
};

TEST(GapNominal, AnotherTrucksParametersAreFittedWithIntervalsThatHoldThem) {
  int covered = 0, total = 0;
  for (int draw = 0; draw < 40; ++draw) {
    Truck t;
    t.problem.z = 1.3 * t.problem.nominal[0].per_sigma - 0.8 * t.problem.nominal[1].per_sigma;
    t.rng.seed(static_cast<unsigned>(draw));
    t.add_noise();
    const NominalFit f = fit_nominal(t.problem, {}, {});
    ASSERT_EQ(f.value.size(), 2u);
    EXPECT_NEAR(f.value[0], 6.2 + 1.3 * 0.6, 0.1);  // 5 sigma of the fit
    EXPECT_NEAR(f.value[1], 36000 - 0.8 * 360, 90);
    for (std::size_t j = 0; j < 2; ++j) {
      const double truth = j == 0 ? 6.2 + 1.3 * 0.6 : 36000 - 0.8 * 360;
      covered += f.lo[j] <= truth && truth <= f.hi[j] ? 1 : 0;
      ++total;
    }
    // The held-out half: the truck's residual is gone, unit noise is left.
    EXPECT_GT(f.chi2_half1_before, 2.0 * f.chi2_half1_after);
    EXPECT_LT(f.chi2_half1_after / (kFeatures / 2), 1.4);
  }
  // 90 % intervals: between 80 and 98 % of 80.
  EXPECT_GE(covered, 64);
  EXPECT_LE(covered, 78);
}

TEST(GapNominal, AnotherTruckIsNotNamedAsTheEffectThatLooksLikeIt) {
  Truck t;
  t.problem.z = 2.0 * t.problem.nominal[0].per_sigma;
  t.add_noise();
  Problem without = t.problem;
  without.nominal.clear();
  const Diagnosis naive = diagnose(without);
  ASSERT_TRUE(naive.chosen) << "without the nominal truck the look-alike effect takes the gap";
  EXPECT_EQ(without.candidates[naive.chosen->effects[0]].name, "effect-0");
  const Diagnosis d = diagnose(t.problem);
  EXPECT_FALSE(d.chosen) << t.problem.candidates[d.chosen->effects[0]].name << " named";
  ASSERT_EQ(d.nominal.value.size(), 2u);
  EXPECT_NEAR(d.nominal.shift_sigma[0], 2.0, 0.1);
}

TEST(GapNominal, AnEffectBesideAnotherTruckIsNamedAndTheTruckStillFitted) {
  Truck t;
  t.problem.z = -1.5 * t.problem.nominal[1].per_sigma + t.problem.candidates[2].response(1.2);
  t.add_noise();
  const Diagnosis d = diagnose(t.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(t.problem.candidates[d.chosen->effects[0]].name, "effect-2");
  EXPECT_NEAR(d.chosen->magnitude[0], 1.2, 0.1);
  EXPECT_NEAR(d.nominal.shift_sigma[1], -1.5, 0.15);
  EXPECT_LT(d.nominal.lo[1], 36000 - 1.5 * 360);
  EXPECT_GT(d.nominal.hi[1], 36000 - 1.5 * 360);
}

TEST(GapNominal, AnEffectANominalParameterStandsForIsListedButNeverNamed) {
  Truck t;
  t.problem.candidates[1].stood_for_by = "mass";
  t.problem.z = t.problem.candidates[1].response(1.5) + t.problem.candidates[2].response(0.8);
  t.add_noise();
  const Diagnosis d = diagnose(t.problem);
  ASSERT_TRUE(d.chosen);
  for (std::size_t e : d.chosen->effects) EXPECT_NE(t.problem.candidates[e].name, "effect-1");
  EXPECT_EQ(t.problem.candidates[d.chosen->effects[0]].name, "effect-2");
  EXPECT_EQ(t.problem.candidates[d.singles.front().effects[0]].name, "effect-1") << "still fitted and listed first";
}

// A truck and an effect placed off the truth, and the residual their re-simulation leaves (here the
// problem's own responses stand for the simulator): one step lands on the truth, as the fit does
// on a model it holds exactly; with no effect, the truck alone does too.
TEST(GapNominal, OneGaussNewtonStepFromWhereAResimulationStoodLandsOnTheTruth) {
  Truck t;
  // Curved: 1.5 u + 0.5 u^2, so that a step must re-centre it to land.
  t.problem.candidates[1] = Candidate::from_two("curved", "unit", 0.0, 0.0, 3.0, 1.0, 2.0 * shape(0.031, 2.0), 2.0,
                                                5.0 * shape(0.031, 2.0));
  const Candidate& effect = t.problem.candidates[1];
  auto plant = [&](const std::vector<double>& shift, double magnitude) {
    Eigen::VectorXd v = effect.response(magnitude);
    for (std::size_t j = 0; j < shift.size(); ++j) v += shift[j] * t.problem.nominal[j].per_sigma;
    return v;
  };
  t.problem.z = plant({0.9, -1.2}, 1.8);
  t.add_noise();
  const Placement from{{-0.4, 0.5}, {1}, {0.6}};
  const Placement to = gauss_newton_step(t.problem, t.problem.z - plant(from.shift_sigma, 0.6), from);
  ASSERT_EQ(to.magnitude_half0.size(), 1u);
  EXPECT_NEAR(to.magnitude_half0[0], 1.8, 0.05);
  EXPECT_NEAR(to.shift_sigma[0], 0.9, 0.1);
  EXPECT_NEAR(to.shift_sigma[1], -1.2, 0.1);
  EXPECT_EQ(to.effects, from.effects);

  t.problem.z = plant({0.9, -1.2}, 0.0);
  t.add_noise();
  const Placement alone{{-0.4, 0.5}, {}, {}};
  const Placement moved = gauss_newton_step(t.problem, t.problem.z - plant(alone.shift_sigma, 0.0), alone);
  EXPECT_TRUE(moved.magnitude_half0.empty());
  EXPECT_NEAR(moved.shift_sigma[0], 0.9, 0.1);
  EXPECT_NEAR(moved.shift_sigma[1], -1.2, 0.1);
}

}  // namespace
}  // namespace roadload::gap
