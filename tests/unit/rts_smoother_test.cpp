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

struct Problem {
  RtsSmoother<1> smoother;
  Eigen::MatrixXd joint;  // posterior covariance of the states at steps 0..kSteps
};

Problem solve(std::mt19937& rng) {
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
  out.smoother.smooth();
  out.joint = info.inverse();
  return out;
}

TEST(RtsSmoother, EachStepsVarianceIsTheBatchSolutions) {
  std::mt19937 rng(3);
  const Problem p = solve(rng);
  for (int k = 0; k <= kSteps; ++k) EXPECT_NEAR(p.smoother.p(static_cast<std::size_t>(k))(0, 0), p.joint(k, k), 1e-12) << k;
}

TEST(RtsSmoother, TheVarianceOfAWeightedSumKeepsTheCovarianceBetweenSteps) {
  std::mt19937 rng(4);
  const Problem p = solve(rng);
  // Gaps, a step taken twice, and the final estimate (index kSteps).
  const std::vector<RtsSmoother<1>::Weight> weights = {{2, 0.5}, {3, 1.0}, {3, 0.25}, {9, 2.0}, {17, 0.75}, {kSteps, 1.5}};
  Eigen::VectorXd w = Eigen::VectorXd::Zero(kSteps + 1);
  for (const auto& x : weights) w(static_cast<Eigen::Index>(x.step)) += x.weight;
  const double batch = w.dot(p.joint * w);
  EXPECT_NEAR(p.smoother.variance_of_sum(Scalar::Ones(), weights), batch, 1e-12 * batch);
  // The two simpler answers bracket it: independent steps too narrow, one shared error too wide.
  double independent = 0, shared = 0;
  for (Eigen::Index k = 0; k <= kSteps; ++k) {
    independent += w(k) * w(k) * p.joint(k, k);
    shared += std::abs(w(k)) * std::sqrt(p.joint(k, k));
  }
  EXPECT_GT(batch, 1.05 * independent);
  EXPECT_LT(batch, 0.5 * shared * shared);
}

TEST(RtsSmoother, NoWeightsNoVariance) {
  std::mt19937 rng(5);
  const Problem p = solve(rng);
  EXPECT_EQ(p.smoother.variance_of_sum(Scalar::Ones(), {}), 0.0);
}

}  // namespace
}  // namespace roadload::ekf
