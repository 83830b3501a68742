#pragma once
// Fixed-interval Rauch-Tung-Striebel smoother over the steps a KalmanCore took: offline, each
// step's estimate then uses the data on both sides of it. Steps are kept in a deque: a drive of
// any length holds what it uses, never a second copy while a vector grows. The backward pass
// writes each step's smoothed estimate over its filtered one and its gain over its Jacobian, which
// it no longer needs; the predicted covariance is computed again from the process noise's
// diagonal, as the filter computed it, rather than kept (1,512 bytes a step of 9 states).
#include <cstddef>
#include <deque>
#include <span>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "roadload/ekf/kalman.hpp"

namespace roadload::ekf {

template <int N>
class RtsSmoother {
 public:
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  using Row = Eigen::Matrix<double, 1, N>;
  struct Weight {
    std::size_t step;  // as smoothed(): size() is the final estimate
    double weight;
  };

  // One prediction: the filtered estimate before it, its Jacobian, the predicted state and the
  // process noise's diagonal (KalmanCore::predict's).
  void record_predict(const Vec& x_filtered, const Mat& p_filtered, const Mat& f, const Vec& x_pred, const Vec& q_diagonal) {
    steps_.push_back({x_filtered, p_filtered, f, x_pred, q_diagonal});
  }
  // The filtered estimate at the end of the recorded interval (after the last update).
  void finish(const Vec& x_last, const Mat& p_last) {
    x_last_ = x_last;
    p_last_ = p_last;
  }

  // Backward pass. After it, smoothed(k) is the estimate at the start of step k.
  void smooth() {
    Vec xs = x_last_;
    Mat ps = p_last_;
    for (std::size_t k = steps_.size(); k-- > 0;) {
      Step& s = steps_[k];
      const Mat p_pred = predicted_covariance<N>(s.p, s.f_then_gain, s.q_diagonal);
      // G = P_f F' P_pred^-1, from a factorisation of the (symmetric) predicted covariance.
      const Eigen::LDLT<Mat> ldlt(p_pred);
      const Mat g = ldlt.solve(s.f_then_gain * s.p).transpose();
      s.f_then_gain = g;
      s.x = s.x + g * (xs - s.x_pred);
      s.p = s.p + g * (ps - p_pred) * g.transpose();
      s.p = 0.5 * (s.p + s.p.transpose());
      xs = s.x;
      ps = s.p;
    }
  }

  std::size_t size() const { return steps_.size(); }
  const Vec& x(std::size_t k) const { return steps_[k].x; }
  // k = size() is the final estimate, as in variance_of_sum.
  const Mat& p(std::size_t k) const { return k < steps_.size() ? steps_[k].p : p_last_; }

  // Variance of sum_k w_k e'x_k over smoothed estimates, `weights` in step order. The estimates of
  // neighbouring steps share most of their data: for i < j their covariance is
  // G_i G_i+1 ... G_j-1 P_j, so the sum is carried forward in one pass rather than taken as
  // independent (too narrow) or as one estimate (too wide).
  double variance_of_sum(const Vec& e, std::span<const Weight> weights) const {
    if (weights.empty()) return 0.0;
    Row carried = Row::Zero();  // sum over earlier steps i of w_i e' G_i ... G_k-1
    double var = 0;
    std::size_t k = weights.front().step;
    for (const Weight& w : weights) {
      for (; k < w.step; ++k) carried = carried * steps_[k].f_then_gain;
      const Vec pe = p(k) * e;
      var += w.weight * w.weight * e.dot(pe) + 2.0 * w.weight * (carried * pe).value();
      carried += w.weight * e.transpose();
    }
    return var;
  }
  void clear() { steps_.clear(); }

 private:
  struct Step {
    Vec x;            // filtered, then smoothed
    Mat p;            // filtered, then smoothed
    Mat f_then_gain;  // the prediction's Jacobian, then the gain that ties this step to the next
    Vec x_pred;
    Vec q_diagonal;
  };
  std::deque<Step> steps_;
  Vec x_last_ = Vec::Zero();
  Mat p_last_ = Mat::Identity();
};

}  // namespace roadload::ekf
