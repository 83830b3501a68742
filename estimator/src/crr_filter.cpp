#include "roadload/crr_filter.hpp"

#include <algorithm>
#include <cmath>

namespace roadload {

void CrrFilter::start(CaptureTime t, double speed_mps) {
  Vec x;
  x << speed_mps, config_.truck.crr_prior, config_.truck.cda_prior_m2;
  Mat p = Mat::Zero();
  p(CrrState::speed, CrrState::speed) = 0.25;
  p(CrrState::crr, CrrState::crr) = config_.truck.crr_sigma * config_.truck.crr_sigma;
  p(CrrState::cda, CrrState::cda) = config_.truck.cda_sigma_m2 * config_.truck.cda_sigma_m2;
  core_.reset(x, p);
  t_ = t;
  started_ = true;
}

double CrrFilter::crr_sigma() const { return std::sqrt(core_.p()(CrrState::crr, CrrState::crr)); }

void CrrFilter::step(double dt, const model::ForceInputs& in) {
  const Vec& x = core_.x();
  const double m = config_.truck.mass_kg;
  const double m_eff = in.effective_mass_kg > 0 ? in.effective_mass_kg : m;
  const double v = x(CrrState::speed);
  const double v_air = v + in.headwind_mps;
  const double weight = m * model::kGravity_mps2;
  const double half_rho = 0.5 * in.air_density_kgpm3;
  const double aero = half_rho * x(CrrState::cda) * v_air * std::abs(v_air);
  const double rolling = x(CrrState::crr) * weight * std::cos(in.grade_rad);
  const double accel = (in.tractive_n - aero - weight * std::sin(in.grade_rad) - rolling) / m_eff;

  Vec next = x;
  Mat f = Mat::Identity();
  Mat q = Mat::Zero();
  if (in.usable) {
    next(CrrState::speed) = v + dt * accel;
    f(CrrState::speed, CrrState::speed) += dt * (-2.0 * half_rho * x(CrrState::cda) * std::abs(v_air) / m_eff);
    f(CrrState::speed, CrrState::crr) = -dt * weight * std::cos(in.grade_rad) / m_eff;
    f(CrrState::speed, CrrState::cda) = -dt * half_rho * v_air * std::abs(v_air) / m_eff;
    const double sf = config_.force_noise_n / m_eff;
    q(CrrState::speed, CrrState::speed) = sf * sf * dt;
  } else {
    // The force balance cannot be trusted (brakes, clutch open): carry the speed by its
    // measurements alone and leave CRR and CdA untouched.
    ++counters_.unusable_predicts;
    const double sf = config_.unusable_force_noise_n / m_eff;
    q(CrrState::speed, CrrState::speed) = sf * sf * dt;
  }
  q(CrrState::crr, CrrState::crr) = config_.crr_walk_per_sqrt_s * config_.crr_walk_per_sqrt_s * dt;
  q(CrrState::cda, CrrState::cda) = config_.cda_walk_per_sqrt_s * config_.cda_walk_per_sqrt_s * dt;
  const Vec x_before = core_.x();
  const Mat p_before = core_.p();
  core_.predict(next, f, q);
  if (smoother_ != nullptr) smoother_->record_predict(x_before, p_before, f, core_.x(), core_.p());
  ++counters_.predicts;
}

void CrrFilter::predict_to(const model::ForceInputs& in) {
  if (!started_ || in.t <= t_) return;
  while (t_ < in.t) {
    const Nanoseconds dt = std::min(config_.max_step, in.t - t_);
    step(to_seconds(dt), in);
    t_ += dt;
  }
}

ekf::UpdateResult CrrFilter::update_speed(CaptureTime t, double speed_mps, double sigma_mps) {
  if (!started_) return {};
  double sigma = sigma_mps;
  if (t < t_) {
    const Nanoseconds lag = t_ - t;
    if (lag > config_.late_window) {
      ++counters_.late_dropped;
      return {};
    }
    // A late speed is used at the current time with the speed change it may have missed
    // (0.5 m/s^2 bounds a loaded truck's acceleration) added to its uncertainty.
    sigma = std::hypot(sigma, 0.5 * to_seconds(lag));
    ++counters_.late_used;
  }
  Eigen::Matrix<double, 1, 1> z, zhat, r;
  z << speed_mps;
  zhat << core_.x()(CrrState::speed);
  r << sigma * sigma;
  Eigen::Matrix<double, 1, CrrState::count> h = Eigen::Matrix<double, 1, CrrState::count>::Zero();
  h(0, CrrState::speed) = 1.0;
  const ekf::UpdateResult res = core_.update<1>(z, zhat, h, r, config_.gate_nis);
  if (res.accepted) {
    ++counters_.updates;
  } else {
    ++counters_.outliers;
  }
  return res;
}

}  // namespace roadload
