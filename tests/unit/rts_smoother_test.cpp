// The smoother against the batch solution of the same linear-Gaussian problem: a random walk seen
// through noise, solved at once as one least-squares problem over every step's state. Its inverse
// information matrix is the joint posterior covariance, cross terms included.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "roadload/ekf/kalman.hpp"
#include "roadload/ekf/rts.hpp"

namespace roadload::ekf {
namespace {

constexpr int kSteps = 24;
constexpr double kPrior = 4.0, kWalk = 0.3, kNoise = 0.5;  // variances

using Scalar = Eigen::Matrix<double, 1, 1>;

using Smoother = RtsSmoother<1>;

struct Problem {
  Smoother smoother;
  Eigen::MatrixXd joint;          // posterior covariance of the states at steps 0..kSteps
  std::vector<double> variances;  // of the sums given to the smoother
};

// The filter run over a random walk, then smoothed with `sums`.
Problem solve(std::mt19937& rng, const std::vector<Smoother::Sum>& sums) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Problem out;
  KalmanCore<1> core;
  core.reset(Scalar::Zero(), Scalar::Constant(kPrior));
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(kSteps + 1, kSteps + 1);
  info(0, 0) = 1.0 / kPrior;
  double truth = std::sqrt(kPrior) * gauss(rng);
  for (int k = 0; k <= kSteps; ++k) {
    const Scalar z = Scalar::Constant(truth + std::sqrt(kNoise) * gauss(rng));
    core.update<1>(z, core.x(), Scalar::Identity(), Scalar::Constant(kNoise), 1e9);
    info(k, k) += 1.0 / kNoise;
    if (k == kSteps) break;
    const Scalar x = core.x(), p = core.p();
    core.predict(x, Scalar::Identity(), Scalar::Constant(kWalk));
    out.smoother.record_predict(x, p, Scalar::Identity(), core.x(), Scalar::Constant(kWalk));
    info(k, k) += 1.0 / kWalk;
    info(k + 1, k + 1) += 1.0 / kWalk;
    info(k, k + 1) -= 1.0 / kWalk;
    info(k + 1, k) -= 1.0 / kWalk;
    truth += std::sqrt(kWalk) * gauss(rng);
  }
  out.smoother.finish(core.x(), core.p());
  out.variances = out.smoother.smooth(sums);
  out.joint = info.inverse();
  return out;
}

Smoother::Sum sum_of(std::vector<Smoother::Weight> weights) { return {Scalar::Ones(), std::move(weights)}; }

TEST(RtsSmoother, EachStepsVarianceIsTheBatchSolutions) {
  std::mt19937 rng(3);
  std::vector<Smoother::Sum> each;
  for (std::size_t k = 0; k <= kSteps; ++k) each.push_back(sum_of({{k, 1.0}}));
  const Problem p = solve(rng, each);
  ASSERT_EQ(p.variances.size(), each.size());
  for (int k = 0; k <= kSteps; ++k) EXPECT_NEAR(p.variances[static_cast<std::size_t>(k)], p.joint(k, k), 1e-12) << k;
}

// A constant-velocity track seen in position: its Jacobian has a full row (position from velocity)
// beside a diagonal one, the shape the smoother keeps in part. Estimates and a sum's variance
// against the batch solution.
TEST(RtsSmoother, ATwoStateTrackIsTheBatchSolution) {
  constexpr int kN = 2, kK = 30;
  constexpr double dt = 0.5, r = 0.4;
  using V = Eigen::Vector2d;
  using M = Eigen::Matrix2d;
  const M f{{1.0, dt}, {0.0, 1.0}};
  const V q{0.01, 0.05};
  const M p0{{9.0, 0.0}, {0.0, 1.0}};
  std::mt19937 rng(6);
  std::normal_distribution<double> gauss(0.0, 1.0);
  KalmanCore<kN> core;
  core.reset(V::Zero(), p0);
  RtsSmoother<kN> smoother;
  const Eigen::Index n = kN * (kK + 1);
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd eta = Eigen::VectorXd::Zero(n);
  info.topLeftCorner<kN, kN>() = p0.inverse();
  const Eigen::Matrix<double, 1, kN> h{1.0, 0.0};
  V truth{3.0 * gauss(rng), gauss(rng)};
  for (int k = 0; k <= kK; ++k) {
    const double z = truth(0) + std::sqrt(r) * gauss(rng);
    core.update<1>(Eigen::Matrix<double, 1, 1>{z}, Eigen::Matrix<double, 1, 1>{core.x()(0)}, h, Eigen::Matrix<double, 1, 1>{r}, 1e9);
    const Eigen::Index i = kN * k;
    info.block<kN, kN>(i, i) += h.transpose() * h / r;
    eta.segment<kN>(i) += h.transpose() * z / r;
    if (k == kK) break;
    const V x = core.x();
    const M p = core.p();
    core.predict(f * x, f, q);
    smoother.record_predict(x, p, f, core.x(), q);
    const M qi = q.cwiseInverse().asDiagonal();
    info.block<kN, kN>(i, i) += f.transpose() * qi * f;
    info.block<kN, kN>(i + kN, i + kN) += qi;
    info.block<kN, kN>(i, i + kN) -= f.transpose() * qi;
    info.block<kN, kN>(i + kN, i) -= qi * f;
    truth = f * truth + V{std::sqrt(q(0)) * gauss(rng), std::sqrt(q(1)) * gauss(rng)};
  }
  smoother.finish(core.x(), core.p());
  RtsSmoother<kN>::Sum velocity_sum{V{0.0, 1.0}, {{4, 1.0}, {5, 1.0}, {20, -2.0}, {kK, 0.5}}};
  const std::vector<double> variance = smoother.smooth({velocity_sum});
  const Eigen::MatrixXd joint = info.inverse();
  const Eigen::VectorXd mean = joint * eta;
  for (int k = 0; k < kK; ++k) {
    for (int s = 0; s < kN; ++s) EXPECT_NEAR(smoother.x(static_cast<std::size_t>(k))(s), mean(kN * k + s), 1e-9) << k << " " << s;
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  for (const auto& x : velocity_sum.weights) w(kN * static_cast<Eigen::Index>(x.step) + 1) += x.weight;
  const double batch = w.dot(joint * w);
  EXPECT_NEAR(variance[0], batch, 1e-10 * batch);
}

TEST(RtsSmoother, TheVarianceOfAWeightedSumKeepsTheCovarianceBetweenSteps) {
  // Gaps, a step taken twice, out of order, and the final estimate (index kSteps).
  const std::vector<Smoother::Weight> weights = {{3, 1.0}, {2, 0.5}, {3, 0.25}, {kSteps, 1.5}, {9, 2.0}, {17, 0.75}};
  // A second sum over part of the same steps, so that two sums are carried at once.
  const std::vector<Smoother::Weight> part = {{9, 1.0}, {12, -0.5}};
  std::mt19937 rng(4);
  const Problem p = solve(rng, {sum_of(weights), sum_of(part)});
  auto batch = [&](const std::vector<Smoother::Weight>& ws) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(kSteps + 1);
    for (const auto& x : ws) w(static_cast<Eigen::Index>(x.step)) += x.weight;
    return std::pair{w.dot(p.joint * w), w};
  };
  const auto [var, w] = batch(weights);
  EXPECT_NEAR(p.variances[0], var, 1e-12 * var);
  EXPECT_NEAR(p.variances[1], batch(part).first, 1e-12 * var);
  // The two simpler answers bracket it: independent steps too narrow, one shared error too wide.
  double independent = 0, shared = 0;
  for (Eigen::Index k = 0; k <= kSteps; ++k) {
    independent += w(k) * w(k) * p.joint(k, k);
    shared += std::abs(w(k)) * std::sqrt(p.joint(k, k));
  }
  EXPECT_GT(var, 1.05 * independent);
  EXPECT_LT(var, 0.5 * shared * shared);
}

TEST(RtsSmoother, NoWeightsNoVariance) {
  std::mt19937 rng(5);
  const Problem p = solve(rng, {sum_of({})});
  ASSERT_EQ(p.variances.size(), 1u);
  EXPECT_EQ(p.variances[0], 0.0);
}

}  // namespace
}  // namespace roadload::ekf
