// The diagnosis's arithmetic on synthetic whitened residuals: candidates with known responses,
// residuals made from them plus unit noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "roadload/gap/diagnosis.hpp"

namespace roadload::gap {
namespace {

constexpr Eigen::Index kProblemFeatures = 240;

struct Synthetic {
  Problem problem;
  std::mt19937_64 rng{42};

  explicit Synthetic(std::size_t candidates) {
    std::normal_distribution<double> normal;
    for (Eigen::Index i = 0; i < kProblemFeatures; ++i) {
      problem.keys.push_back({"run", i < kProblemFeatures / 2 ? "torque_nm" : "psd_db:TLF1", "cell " + std::to_string(i / 2),
                              static_cast<std::uint8_t>(i % 2)});
    }
    for (std::size_t c = 0; c < candidates; ++c) {
      // Each response a smooth shape over the features, with a little curvature.
      Eigen::VectorXd d1(kProblemFeatures), d2(kProblemFeatures);
      const double phase = normal(rng), freq = 0.02 + 0.01 * static_cast<double>(c);
      for (Eigen::Index i = 0; i < kProblemFeatures; ++i) {
        const double shape = std::sin(freq * static_cast<double>(i) + phase) +
                             0.3 * static_cast<double>(static_cast<Eigen::Index>(c % 3) == i % 3);
        d1(i) = 2.0 * shape;  // at magnitude 1
        d2(i) = 4.4 * shape;  // at magnitude 2: 2 u + 0.1 u^2
      }
      problem.candidates.push_back(Candidate::from_two("effect-" + std::to_string(c), "unit", 0.0, 0.0, 3.0, 1.0, d1, 2.0, d2));
    }
    problem.z = Eigen::VectorXd::Zero(kProblemFeatures);
  }
  void add_noise() {
    std::normal_distribution<double> normal;
    for (Eigen::Index i = 0; i < kProblemFeatures; ++i) problem.z(i) += normal(rng);
  }
  std::string chosen_name(const Diagnosis& d, std::size_t i = 0) const {
    return d.chosen ? problem.candidates[d.chosen->effects[i]].name : "none";
  }
  // A nominal mass whose response per sigma is a cosine of this amplitude over the features.
  Eigen::VectorXd add_mass(double amplitude) {
    Eigen::VectorXd truck(kProblemFeatures);
    for (Eigen::Index i = 0; i < kProblemFeatures; ++i) truck(i) = amplitude * std::cos(0.05 * static_cast<double>(i));
    problem.nominal.push_back({"mass", "kg", 30000.0, 360.0, truck});
    return truck;
  }
  // Candidate 0's response made its own part (none of it along the truck's) plus `along` truck
  // sigmas; its own part returned.
  Eigen::VectorXd tie_effect_0_to(const Eigen::VectorXd& truck, double along) {
    Eigen::VectorXd own = problem.candidates[0].response(1.0);
    own -= truck * (own.dot(truck) / truck.squaredNorm());
    const Eigen::VectorXd response = own + along * truck;
    problem.candidates[0] = Candidate::from_two("effect-0", "unit", 0.0, 0.0, 3.0, 1.0, response, 2.0, 2.0 * response);
    return own;
  }
};

TEST(GapCandidate, TwoSimulationsGiveTheQuadraticResponseExactly) {
  Eigen::VectorXd d1(2), d2(2);
  // response(u) = 3 u - 0.5 u^2 and -u + 2 u^2, simulated at base + 1 and base + 4 (base 0.5).
  d1 << 2.5, 1.0;
  d2 << 4.0, 28.0;
  const Candidate c = Candidate::from_two("x", "m", 0.5, 0.0, 5.0, 1.5, d1, 4.5, d2);
  const Eigen::VectorXd r = c.response(0.5 + 2.0);
  EXPECT_NEAR(r(0), 3.0 * 2.0 - 0.5 * 4.0, 1e-12);
  EXPECT_NEAR(r(1), -2.0 + 2.0 * 4.0, 1e-12);
  EXPECT_NEAR(c.response(0.5).norm(), 0.0, 1e-12);
}

TEST(GapDiagnosis, NamesTheEffectThatMadeTheResidualWithItsMagnitudeInsideTheInterval) {
  Synthetic s(6);
  s.problem.z = s.problem.candidates[3].response(1.7);
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(s.chosen_name(d), "effect-3");
  ASSERT_EQ(d.chosen->effects.size(), 1u);
  EXPECT_LT(d.chosen->lo[0], 1.7);
  EXPECT_GT(d.chosen->hi[0], 1.7);
  EXPECT_NEAR(d.chosen->magnitude[0], 1.7, 0.1);
  EXPECT_GT(d.chosen->gain, 1000.0);
}

// Effect 3 made the residual; candidate 5 is its twin, differing by less than the noise can tell.
Synthetic with_twin() {
  Synthetic s(6);
  Candidate twin = s.problem.candidates[3];
  twin.name = "twin";
  twin.a += 0.02 * s.problem.candidates[1].a;
  s.problem.candidates[5] = twin;
  s.problem.z = s.problem.candidates[3].response(1.7);
  s.add_noise();
  return s;
}

// Two effects whose signatures differ by less than noise can tell: the one named lists the other
// as a rival; effects whose fits fall short by more than noise alone gives are not listed.
TEST(GapDiagnosis, ListsTheRivalsTheDrivesCannotTellApart) {
  Synthetic s = with_twin();
  Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  const std::string named = s.chosen_name(d);
  ASSERT_TRUE(named == "effect-3" || named == "twin") << named;
  ASSERT_EQ(d.rivals.size(), 1u);
  EXPECT_EQ(s.problem.candidates[d.rivals[0].effects[0]].name, named == "twin" ? "effect-3" : "twin");
  // A rival must clear twice its own noise: a twin that fits noise as well as this gap does not.
  s.problem.candidates[d.rivals[0].effects[0]].null_gain = 10.0 * d.chosen->gain;
  d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_TRUE(d.rivals.empty());
}

// Beside an effect named just past the rule's gain, a twin just short of it is listed: the drives
// tell them apart no better than there.
TEST(GapDiagnosis, ARivalJustShortOfTheRulesGainIsListed) {
  Synthetic s = with_twin();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  ASSERT_EQ(d.rivals.size(), 1u);
  DecisionRule rule;
  rule.null_gain = 0.5 * (d.chosen->gain + d.rivals[0].gain);
  ASSERT_GT(d.chosen->gain - d.rivals[0].gain, 0.0);
  const Diagnosis past = diagnose(s.problem, rule);
  ASSERT_TRUE(past.chosen);
  EXPECT_EQ(s.chosen_name(past), s.chosen_name(d));
  const std::size_t rival = d.rivals[0].effects[0];
  const auto listed = std::find_if(past.rivals.begin(), past.rivals.end(), [&](const Fit& f) { return f.effects[0] == rival; });
  ASSERT_NE(listed, past.rivals.end());
  EXPECT_LT(listed->gain, rule.null_gain);
}

TEST(GapDiagnosis, NamesNothingInPureNoise) {
  Synthetic s(6);
  for (int draw = 0; draw < 50; ++draw) {
    s.problem.z.setZero();
    s.add_noise();
    const Diagnosis d = diagnose(s.problem);
    EXPECT_FALSE(d.chosen) << "draw " << draw << " named " << s.chosen_name(d) << " with gain " << d.chosen->gain;
  }
}

TEST(GapDiagnosis, FindsTwoEffectsAtOnce) {
  Synthetic s(6);
  s.problem.z = s.problem.candidates[1].response(2.0) + s.problem.candidates[4].response(1.0);
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  ASSERT_EQ(d.chosen->effects.size(), 2u);
  const std::set<std::string> named{s.chosen_name(d, 0), s.chosen_name(d, 1)};
  EXPECT_EQ(named, (std::set<std::string>{"effect-1", "effect-4"}));
}

// The drive has effect 0 and a leftover that no candidate is (what a nominal truck's fit leaves).
// Effects 1 and 2 are made so that together they reproduce both: 1 is effect 0 plus a pattern c,
// 2 takes c back and carries the leftover. The pair 1 + 2 fits best, but it is not an extension of
// the effect the single fits found, and naming it would name an effect that is not there.
TEST(GapDiagnosis, ASecondEffectExtendsTheNamedOneAndNeverReplacesIt) {
  Synthetic s(3);
  Eigen::VectorXd x(kProblemFeatures), c(kProblemFeatures), leftover(kProblemFeatures);
  for (Eigen::Index i = 0; i < kProblemFeatures; ++i) {
    const auto t = static_cast<double>(i);
    x(i) = 2.0 * std::sin(0.05 * t);
    c(i) = 2.0 * std::cos(0.11 * t);
    leftover(i) = std::sin(0.23 * t + 1.0);
  }
  const Eigen::VectorXd y = x + c, z = leftover - c;
  const std::array<const Eigen::VectorXd*, 3> shapes{&x, &y, &z};
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    s.problem.candidates[k] = Candidate::from_two("effect-" + std::to_string(k), "unit", 0.0, 0.0, 3.0, 1.0, *shapes[k], 2.0,
                                                  2.0 * *shapes[k]);
  }
  s.problem.z = 1.5 * x + 1.5 * leftover;
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  ASSERT_TRUE(d.best_pair);
  EXPECT_EQ(s.problem.candidates[d.singles.front().effects[0]].name, "effect-0");
  EXPECT_EQ(s.chosen_name(d), "effect-0");
  EXPECT_EQ(d.best_pair->effects[0], d.chosen->effects[0]);
  // The pair left out fits the drive better than the single named.
  const Fit others = fit_effects(s.problem, {1, 2});
  EXPECT_GT(others.gain, d.singles.front().gain + 100.0) << others.gain << " against " << d.singles.front().gain;
}

TEST(GapDiagnosis, AFitThatDoesNotCarryToTheOtherHalfIsNotNamed) {
  // The residual has effect 2's shape on half 0 only: a fit on half 0 predicts half 1 wrongly.
  Synthetic s(6);
  const Eigen::VectorXd r = s.problem.candidates[2].response(2.0);
  for (Eigen::Index i = 0; i < kProblemFeatures; ++i) s.problem.z(i) = i % 2 == 0 ? r(i) : 0.0;
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  EXPECT_FALSE(d.chosen) << s.chosen_name(d);
  EXPECT_LT(d.singles.front().gain, 100.0);
}

TEST(GapDiagnosis, OfTwoLookalikesNamesTheOneWhoseFittedMagnitudeIsRealistic) {
  Synthetic s(2);
  s.problem.candidates[1].a = s.problem.candidates[0].a;
  s.problem.candidates[1].b = s.problem.candidates[0].b;
  s.problem.candidates[0].realistic_lo = 2.0;  // 1.0 is far below where this effect is met
  s.problem.candidates[0].realistic_hi = 3.0;
  s.problem.candidates[1].realistic_lo = 0.5;
  s.problem.candidates[1].realistic_hi = 1.5;
  s.problem.z = s.problem.candidates[0].response(1.0);
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(s.chosen_name(d), "effect-1");
  EXPECT_LT(d.singles.back().plausibility, 0.01);
}

TEST(GapDiagnosis, AnEffectThatFitsOnlyBesideAnImplausibleTruckIsNotNamed) {
  // The drive holds effect 0 and a leftover. Effect 1 reproduces both, but only beside a truck six
  // of its prior's sigmas from the model's, as worn tread does beside a tyre radius far off.
  Synthetic s(3);
  const Eigen::VectorXd gap = s.problem.candidates[0].response(1.0);
  const Eigen::VectorXd leftover = 0.5 * s.problem.candidates[2].response(1.0);
  Eigen::VectorXd truck(kProblemFeatures);
  for (Eigen::Index i = 0; i < kProblemFeatures; ++i) truck(i) = 2.0 * std::cos(0.05 * static_cast<double>(i));
  s.problem.nominal.push_back({"tire radius", "m", 0.5, 0.004, truck});
  const Eigen::VectorXd lookalike = gap + leftover - 6.0 * truck;
  s.problem.candidates[1] = Candidate::from_two("effect-1", "unit", 0.0, 0.0, 3.0, 1.0, lookalike, 2.0, 2.0 * lookalike);
  s.problem.candidates.pop_back();
  s.problem.z = gap + leftover;
  s.add_noise();
  DecisionRule any_truck;
  any_truck.truck_sigmas = std::numeric_limits<double>::infinity();
  const Diagnosis blind = diagnose(s.problem, any_truck);
  ASSERT_TRUE(blind.chosen);
  EXPECT_EQ(s.chosen_name(blind), "effect-1");  // what the rule is for
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(s.chosen_name(d), "effect-0");
  const auto lookalike_fit = std::find_if(d.singles.begin(), d.singles.end(), [](const Fit& f) { return f.effects[0] == 1; });
  ASSERT_NE(lookalike_fit, d.singles.end());
  EXPECT_GT(lookalike_fit->truck_sigma, 5.0);
  EXPECT_LT(lookalike_fit->truck_plausibility, 0.05);
}

TEST(GapDiagnosis, AnEffectThatExplainsTheDriveBesideTheTruckFittedAloneIsNamed) {
  // Effect 0's response carries a part along the truck's that the drive lacks. Fitted freely, the
  // truck runs six sigmas out to cancel that part; left where it fits alone, the effect still
  // explains most of the drive, and that is what it scores.
  Synthetic s(2);
  s.problem.z = s.tie_effect_0_to(s.add_mass(0.13), 9.0);
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(s.chosen_name(d), "effect-0");
  const Fit& f = d.singles.front();
  EXPECT_GT(f.truck_sigma, 5.0);
  EXPECT_LT(f.truck_plausibility, 0.01);
  EXPECT_GT(f.gain_truck_kept, 200.0);
  EXPECT_TRUE(f.scored_truck_kept);
  EXPECT_NEAR(f.gain, f.gain_truck_kept, 1e-9);  // the smaller of the kept and the free gains
}

TEST(GapDiagnosis, AnEffectThatBringsARunawayTruckBackIsBelieved) {
  // Fitted alone, the truck runs ten sigmas out to take up the effect; beside it, five. The effect
  // needs a truck beyond the spreads but nearer than the truck alone: it is not penalised.
  Synthetic s(1);
  const Eigen::VectorXd truck = s.add_mass(2.0);
  s.problem.z = s.tie_effect_0_to(truck, 5.0) + 10.0 * truck;
  s.add_noise();
  const Diagnosis d = diagnose(s.problem);
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(s.chosen_name(d), "effect-0");
  EXPECT_GT(d.singles.front().truck_sigma, 4.0);
  EXPECT_GT(d.singles.front().truck_plausibility, 0.99);
  EXPECT_GT(std::abs(fit_nominal(s.problem, {}, {}).shift_sigma.front()), 8.0);  // the truck alone
}

TEST(GapLocate, RanksTheChannelWithTheExcessFirstAndNamesItsWorstPlace) {
  Synthetic s(1);
  s.add_noise();
  s.problem.z(kProblemFeatures - 7) = 12.0;  // one feature of the vibration channel
  s.problem.z(kProblemFeatures - 9) = 6.0;
  const auto where = locate(s.problem.keys, s.problem.z, 5);
  ASSERT_FALSE(where.empty());
  EXPECT_EQ(where.front().channel, "psd_db:TLF1");
  EXPECT_EQ(where.front().worst_where, s.problem.keys[kProblemFeatures - 7].where);
  EXPECT_DOUBLE_EQ(where.front().worst_z, 12.0);
  EXPECT_GT(where.front().significance, 5.0);
}

TEST(GapRms, OfOneHalfCountsOnlyItsValidFeatures) {
  Synthetic s(1);
  for (Eigen::Index i = 0; i < kProblemFeatures; ++i) s.problem.z(i) = i % 2 == 0 ? 2.0 : 4.0;
  s.problem.z(3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(rms(s.problem.z, s.problem.keys, 0), 2.0);
  EXPECT_DOUBLE_EQ(rms(s.problem.z, s.problem.keys, 1), 4.0);
}

}  // namespace
}  // namespace roadload::gap
