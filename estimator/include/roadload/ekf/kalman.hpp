#pragma once
// A fixed-size extended Kalman filter core: the caller linearises its model and hands over the
// Jacobians; this class owns the state, the covariance and the numerically safe update. No heap:
// every matrix is an Eigen fixed-size type, so a step costs the same every time.
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace roadload::ekf {

struct UpdateResult {
  bool accepted = false;
  double nis = 0.0;         // normalised innovation squared, y' S^-1 y
  double innovation = 0.0;  // first component of y, for logs
};

// F P F' + Q for a diagonal Q (white noise on each state), made exactly symmetric. One function
// for the filter and the smoother, which recomputes it rather than keep a copy per step.
template <int N>
Eigen::Matrix<double, N, N> predicted_covariance(const Eigen::Matrix<double, N, N>& p, const Eigen::Matrix<double, N, N>& f,
                                                 const Eigen::Matrix<double, N, 1>& q_diagonal) {
  Eigen::Matrix<double, N, N> out = f * p * f.transpose();
  out.diagonal() += q_diagonal;
  return 0.5 * (out + out.transpose());
}

template <int N>
class KalmanCore {
 public:
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;

  void reset(const Vec& x, const Mat& p) {
    x_ = x;
    p_ = p;
  }

  // Consider states (Schmidt-Kalman): their uncertainty enters every other state's covariance,
  // but measurements never move them. For parameters the data cannot separate (aero drag and a
  // torque bias at one steady speed), so that model errors are not absorbed into them.
  void set_consider(int index, bool consider) { consider_(index) = consider ? 0.0 : 1.0; }

  // x <- x_next (the caller integrated the nonlinear model), P <- F P F' + Q, Q diagonal.
  void predict(const Vec& x_next, const Mat& f, const Vec& q_diagonal) {
    x_ = x_next;
    p_ = predicted_covariance<N>(p_, f, q_diagonal);
  }

  // Measurement z of dimension M with prediction h(x) = zhat and Jacobian H. The innovation is
  // rejected when its NIS exceeds `gate` (a chi-square quantile); S is factored, never inverted,
  // and P is updated in Joseph form, which holds for any gain (the consider states' rows are zero),
  // so it stays symmetric positive definite.
  template <int M>
  UpdateResult update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 1>& zhat,
                      const Eigen::Matrix<double, M, N>& h, const Eigen::Matrix<double, M, M>& r, double gate) {
    const Eigen::Matrix<double, M, 1> y = z - zhat;
    const Eigen::Matrix<double, M, M> s = h * p_ * h.transpose() + r;
    const Eigen::LDLT<Eigen::Matrix<double, M, M>> ldlt(s);
    UpdateResult out;
    out.nis = y.dot(ldlt.solve(y));
    out.innovation = y(0);
    if (!(out.nis <= gate)) return out;
    // K = P H' S^-1, computed as (S^-1 H P)' since S and P are symmetric.
    const Eigen::Matrix<double, M, N> hp = h * p_;
    const Eigen::Matrix<double, M, N> s_inv_hp = ldlt.solve(hp);
    const Eigen::Matrix<double, N, M> k = consider_.asDiagonal() * s_inv_hp.transpose();
    x_ += k * y;
    const Mat a = Mat::Identity() - k * h;
    p_ = a * p_ * a.transpose() + k * r * k.transpose();
    p_ = 0.5 * (p_ + p_.transpose());
    out.accepted = true;
    return out;
  }

  const Vec& x() const { return x_; }
  Vec& x() { return x_; }
  const Mat& p() const { return p_; }

 private:
  Vec x_ = Vec::Zero();
  Mat p_ = Mat::Identity();
  Vec consider_ = Vec::Ones();  // 1: updated, 0: considered only
};

}  // namespace roadload::ekf
