#pragma once
// Fixed-interval Rauch-Tung-Striebel smoother over the steps a KalmanCore took: offline, each
// step's estimate then uses the data on both sides of it.
//
// Memory is what bounds an hour's analysis, so a step keeps only what the backward pass reads:
//  - the filtered covariance as its lower triangle (the filter keeps it exactly symmetric);
//  - the Jacobian as its diagonal plus those rows that have more (a filter's Jacobian is mostly
//    random walks and decays, with a few rows of dynamics);
//  - no predicted covariance: it is computed again from the process noise's diagonal, as the
//    filter computed it;
//  - no smoothed covariance or gain: the variances the caller needs, of weighted sums of smoothed
//    estimates, are accumulated during the pass (smooth()), and the smoothed state takes the
//    filtered one's place.
// A 9-state step is 656 bytes plus 72 per full Jacobian row, where keeping every matrix took 1,512.
// The full rows are freed as the pass reads them.
#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "roadload/ekf/kalman.hpp"

namespace roadload::ekf {

template <int N>
class RtsSmoother {
  static_assert(N <= 32, "the Jacobian's full rows are a 32-bit mask");

 public:
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  using Row = Eigen::Matrix<double, 1, N>;
  struct Weight {
    std::size_t step;  // as x(); size() is the final estimate
    double weight;
  };
  // sum_k w_k e'x_k over smoothed estimates: any order, a step may appear more than once.
  struct Sum {
    Vec e = Vec::Zero();
    std::vector<Weight> weights;
  };

  // One prediction: the filtered estimate before it, its Jacobian, the predicted state and the
  // process noise's diagonal (KalmanCore::predict's).
  void record_predict(const Vec& x_filtered, const Mat& p_filtered, const Mat& f, const Vec& x_pred, const Vec& q_diagonal) {
    Step& s = steps_.emplace_back();
    s.x = x_filtered;
    s.p = pack(p_filtered);
    s.f_diagonal = f.diagonal();
    for (int r = 0; r < N; ++r) {
      if (!off_diagonal_zero(f, r)) {
        s.f_rows |= std::uint32_t{1} << r;
        f_rows_.push_back(f.row(r));
      }
    }
    s.x_pred = x_pred;
    s.q_diagonal = q_diagonal;
  }
  // The filtered estimate at the end of the recorded interval (after the last update).
  void finish(const Vec& x_last, const Mat& p_last) {
    x_last_ = x_last;
    p_last_ = p_last;
  }

  // Backward pass. After it, x(k) is the smoothed estimate at the start of step k. Returns each
  // sum's variance (the sums' weights are reordered in place): the estimates of neighbouring steps share most of
  // their data (for i < j their covariance is G_i G_i+1 ... G_j-1 P_j), so each sum carries
  // u_k = sum over its later steps j of w_j G_k ... G_j-1 P_j e back through the steps between
  // its first and last weight, rather than taking the steps as independent (too narrow) or as one
  // estimate (too wide).
  std::vector<double> smooth(std::vector<Sum> sums = {}) {
    const std::size_t n = steps_.size();
    Accumulators acc(sums, n);
    Vec xs = x_last_;
    Mat ps = p_last_;
    acc.visit(n, ps);
    for (std::size_t k = n; k-- > 0;) {
      Step& s = steps_[k];
      const Mat p = unpack(s.p);
      const Mat f = jacobian(s);
      const Mat p_pred = predicted_covariance<N>(p, f, s.q_diagonal);
      // G = P_f F' P_pred^-1, from a factorisation of the (symmetric) predicted covariance.
      const Eigen::LDLT<Mat> ldlt(p_pred);
      const Mat g = ldlt.solve(f * p).transpose();
      xs = s.x + g * (xs - s.x_pred);
      ps = p + g * (ps - p_pred) * g.transpose();
      ps = 0.5 * (ps + ps.transpose());
      s.x = xs;
      acc.carry(g);
      acc.visit(k, ps);
    }
    return acc.variances();
  }

  std::size_t size() const { return steps_.size(); }
  const Vec& x(std::size_t k) const { return steps_[k].x; }
  void clear() {
    steps_.clear();
    f_rows_.clear();
  }

 private:
  static constexpr int kPacked = N * (N + 1) / 2;
  struct Step {
    Vec x;                          // filtered, then smoothed
    std::array<double, kPacked> p;  // lower triangle, row by row
    Vec f_diagonal;
    std::uint32_t f_rows = 0;  // rows of the Jacobian kept whole in f_rows_
    Vec x_pred;
    Vec q_diagonal;
  };

  // One sum's backward accumulation: its weights by step, last first, same steps merged.
  struct Accumulator {
    const Sum* sum;
    std::span<const Weight> weights;
    std::size_t next = 0;
    Vec carried = Vec::Zero();  // w_k P_k e + u_k at the step last visited
    double variance = 0;
  };
  class Accumulators {
   public:
    Accumulators(std::vector<Sum>& sums, std::size_t last) : all_(sums.size()) {
      for (std::size_t i = 0; i < sums.size(); ++i) {
        Accumulator& a = all_[i];
        a.sum = &sums[i];
        merge(sums[i].weights, last);
        a.weights = sums[i].weights;
        if (!a.weights.empty()) order_.push_back(i);
      }
      std::sort(order_.begin(), order_.end(),
                [&](std::size_t a, std::size_t b) { return all_[a].weights.front().step > all_[b].weights.front().step; });
    }
    // u_k = G_k (w_k+1 P_k+1 e + u_k+1) for every sum with weights on both sides of step k.
    void carry(const Mat& g) {
      for (const std::size_t i : active_) all_[i].carried = g * all_[i].carried;
    }
    void visit(std::size_t k, const Mat& ps) {
      for (; started_ < order_.size() && all_[order_[started_]].weights.front().step >= k; ++started_) {
        active_.push_back(order_[started_]);
      }
      for (std::size_t j = 0; j < active_.size();) {
        Accumulator& a = all_[active_[j]];
        assert(a.weights[a.next].step <= k);
        if (a.weights[a.next].step == k) {
          const double w = a.weights[a.next].weight;
          const Vec pe = ps * a.sum->e;
          a.variance += w * w * a.sum->e.dot(pe) + 2.0 * w * a.sum->e.dot(a.carried);
          a.carried += w * pe;
          ++a.next;
        }
        if (a.next == a.weights.size()) {
          active_[j] = active_.back();
          active_.pop_back();
        } else {
          ++j;
        }
      }
    }
    std::vector<double> variances() const {
      std::vector<double> out;
      out.reserve(all_.size());
      for (const Accumulator& a : all_) out.push_back(a.variance);
      return out;
    }

   private:
    // Last step first, one weight a step; steps beyond `last` are not estimates and are left out.
    static void merge(std::vector<Weight>& w, std::size_t last) {
      assert(std::all_of(w.begin(), w.end(), [&](const Weight& x) { return x.step <= last; }));
      std::erase_if(w, [&](const Weight& x) { return x.step > last; });
      std::sort(w.begin(), w.end(), [](const Weight& a, const Weight& b) { return a.step > b.step; });
      std::size_t kept = 0;
      for (std::size_t i = 0; i < w.size(); ++i) {
        if (kept > 0 && w[kept - 1].step == w[i].step) {
          w[kept - 1].weight += w[i].weight;
        } else {
          w[kept++] = w[i];
        }
      }
      w.resize(kept);
    }

    std::vector<Accumulator> all_;
    std::vector<std::size_t> order_;  // sums with weights, latest last step first
    std::size_t started_ = 0;
    std::vector<std::size_t> active_;
  };

  static bool off_diagonal_zero(const Mat& f, int r) {
    for (int c = 0; c < N; ++c) {
      if (c != r && f(r, c) != 0.0) return false;
    }
    return true;
  }
  static std::array<double, kPacked> pack(const Mat& p) {
    std::array<double, kPacked> out;
    std::size_t i = 0;
    for (int r = 0; r < N; ++r) {
      for (int c = 0; c <= r; ++c) out[i++] = p(r, c);
    }
    return out;
  }
  static Mat unpack(const std::array<double, kPacked>& packed) {
    Mat p;
    std::size_t i = 0;
    for (int r = 0; r < N; ++r) {
      for (int c = 0; c <= r; ++c) p(r, c) = p(c, r) = packed[i++];
    }
    return p;
  }
  // The step's Jacobian, its full rows taken off the back of f_rows_ (the pass runs backwards).
  Mat jacobian(const Step& s) {
    Mat f = s.f_diagonal.asDiagonal();
    for (int r = N; r-- > 0;) {
      if ((s.f_rows >> r & 1u) == 0) continue;
      f.row(r) = f_rows_.back();
      f_rows_.pop_back();
    }
    return f;
  }

  std::deque<Step> steps_;
  std::deque<Row> f_rows_;
  Vec x_last_ = Vec::Zero();
  Mat p_last_ = Mat::Identity();
};

}  // namespace roadload::ekf
