#include "roadload/crr_filter.hpp"

#include <algorithm>
#include <cmath>

namespace roadload {

namespace {

struct Offset {
  double sigma = 0, phi = 1;  // stationary sigma, decay over the step
};
struct Decay {
  double phi = 1, q = 0;
};

// Two independent stationary speed offsets carried as one first-order Gauss-Markov state: the
// sum's variance, and the decay that gives the sum's change over the step.
Decay lumped(Offset a, Offset b) {
  const double variance = a.sigma * a.sigma + b.sigma * b.sigma;
  const double change = a.sigma * a.sigma * (1.0 - a.phi * a.phi) + b.sigma * b.sigma * (1.0 - b.phi * b.phi);
  if (!(variance > 0)) return {a.phi, 0.0};
  return {std::sqrt(std::max(0.0, 1.0 - change / variance)), change};
}

}  // namespace

double eec3_quantization_sigma_nm(double reference_torque_nm) { return reference_torque_nm * 0.01 * std::sqrt(2.0 / 12.0); }

void CrrFilter::start(CaptureTime t, double speed_mps, std::optional<double> torque_bias_sigma_nm) {
  Vec x;
  x << speed_mps, config_.truck.crr_prior, config_.truck.cda_prior_m2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  x(CrrState::torque_scale) = config_.torque_scale_held;
  Mat p = Mat::Zero();
  p(CrrState::speed, CrrState::speed) = 0.25;
  p(CrrState::crr, CrrState::crr) = config_.truck.crr_sigma * config_.truck.crr_sigma;
  p(CrrState::cda, CrrState::cda) = config_.truck.cda_sigma_m2 * config_.truck.cda_sigma_m2;
  const double bias_sigma = torque_bias_sigma_nm.value_or(config_.torque_bias_sigma_nm);
  p(CrrState::torque_bias, CrrState::torque_bias) = bias_sigma * bias_sigma;
  const double rho = std::clamp(config_.truck.cda_torque_bias_correlation, -1.0, 1.0);
  p(CrrState::cda, CrrState::torque_bias) = p(CrrState::torque_bias, CrrState::cda) = rho * config_.truck.cda_sigma_m2 * bias_sigma;
  p(CrrState::torque_scale, CrrState::torque_scale) = config_.truck.torque_scale_sigma * config_.truck.torque_scale_sigma;
  p(CrrState::efficiency_scale, CrrState::efficiency_scale) = config_.truck.efficiency_scale_sigma *
                                                              config_.truck.efficiency_scale_sigma;
  const double mass_share = config_.truck.mass_kg > 0 ? config_.truck.mass_sigma_kg / config_.truck.mass_kg : 0.0;
  p(CrrState::mass_scale, CrrState::mass_scale) = mass_share * mass_share;
  core_.reset(x, p);
  core_.set_consider(CrrState::cda, !config_.estimate_cda);
  core_.set_consider(CrrState::torque_bias, true);
  // The grade error is estimated: it lasts tens of metres, so the speed it has just bent tells
  // what it does next. Only considered, it widened the intervals but left its share in the CRR
  // (docs/journal.md, 2026-11-26).
  core_.set_consider(CrrState::torque_scale, true);
  core_.set_consider(CrrState::efficiency_scale, true);
  core_.set_consider(CrrState::mass_scale, !config_.estimate_mass);
  t_ = t;
  started_ = true;
}

double CrrFilter::mass_sigma_kg() const {
  return config_.truck.mass_kg * std::sqrt(core_.p()(CrrState::mass_scale, CrrState::mass_scale));
}

double CrrFilter::crr_sigma() const { return std::sqrt(core_.p()(CrrState::crr, CrrState::crr)); }

void CrrFilter::step(double dt, const model::ForceInputs& in, double crr_jump_variance) {
  const Vec& x = core_.x();
  const double m0 = config_.truck.mass_kg;
  // The torque and efficiency scales stay at zero (considered, never updated), the mass scale too
  // unless estimated; all written out so the Jacobian is the model's.
  const double mass_scale = 1.0 + x(CrrState::mass_scale);
  const double m = m0 * mass_scale;
  const double m_eff = (in.effective_mass_kg > 0 ? in.effective_mass_kg : m0) + (m - m0);
  const double v = x(CrrState::speed);
  const double v_air = v + in.headwind_mps;
  const double weight = m * model::kGravity_mps2;
  const double half_rho = 0.5 * in.air_density_kgpm3;
  const model::Resistances r = model::resistances(m, x(CrrState::crr), x(CrrState::cda), in.air_density_kgpm3, v_air, in.grade_rad,
                                                  x(CrrState::grade_error));
  const double aero = r.aero_n;
  const double bias_n = in.wheel_force_per_flywheel_nm * x(CrrState::torque_bias);
  const double tractive = in.tractive_n * (1.0 + x(CrrState::efficiency_scale)) + in.indicated_force_n * x(CrrState::torque_scale);
  const double accel = (tractive + bias_n - aero - r.grade_n - r.rolling_n) / m_eff;

  Vec next = x;
  Mat f = Mat::Identity();
  Vec q = Vec::Zero();  // white process noise, one variance per state
  if (in.usable) {
    next(CrrState::speed) = v + dt * accel;
    f(CrrState::speed, CrrState::speed) += dt * (-2.0 * half_rho * x(CrrState::cda) * std::abs(v_air) / m_eff);
    f(CrrState::speed, CrrState::crr) = -dt * weight * std::cos(in.grade_rad) / m_eff;
    f(CrrState::speed, CrrState::cda) = -dt * half_rho * v_air * std::abs(v_air) / m_eff;
    f(CrrState::speed, CrrState::torque_bias) = dt * in.wheel_force_per_flywheel_nm / m_eff;
    f(CrrState::speed, CrrState::grade_error) = -dt * weight * std::cos(in.grade_rad) / m_eff;
    f(CrrState::speed, CrrState::torque_scale) = dt * in.indicated_force_n / m_eff;
    f(CrrState::speed, CrrState::efficiency_scale) = dt * in.tractive_n / m_eff;
    // The mass moves the weight's forces and the inertia: d(accel)/d(scale) at the scale's value.
    f(CrrState::speed, CrrState::mass_scale) = dt * (-(r.grade_n + r.rolling_n) / mass_scale - accel * m0) / m_eff;
    const double sf = std::hypot(config_.force_noise_n, config_.aero_force_noise_per_sqrt_hz * aero) / m_eff;
    q(CrrState::speed) = sf * sf * dt;
  } else {
    // The force balance cannot be trusted (brakes, clutch open): carry the speed by its
    // measurements alone and leave the parameters untouched.
    ++counters_.unusable_predicts;
    const double sf = config_.unusable_force_noise_n / m_eff;
    q(CrrState::speed) = sf * sf * dt;
  }
  q(CrrState::crr) = config_.crr_walk_per_sqrt_s * config_.crr_walk_per_sqrt_s * dt + crr_jump_variance;
  q(CrrState::cda) = config_.cda_walk_per_sqrt_s * config_.cda_walk_per_sqrt_s * dt;
  const double bias_walk = config_.torque_bias_walk_nm_per_sqrt_s;
  q(CrrState::torque_bias) = bias_walk * bias_walk * dt;
  // The grade error decorrelates with distance travelled; its variance tends to the profile's here.
  const double phi = std::exp(-std::abs(v) * dt / config_.grade_error_correlation_m);
  f(CrrState::grade_error, CrrState::grade_error) = phi;
  next(CrrState::grade_error) = phi * x(CrrState::grade_error);
  q(CrrState::grade_error) = in.grade_sigma_rad * in.grade_sigma_rad * (1.0 - phi * phi);
  // The ripple: the road's, a Gauss-Markov process along the road as the inputs give it, and the
  // force errors that integrate to nothing, one in time (config); each tick's share of the latter
  // has the density of white force noise of the same size.
  const double phi_road = std::exp(-std::abs(v) * dt / std::max(in.ripple_correlation_m, 1e-3));
  const double tau_s = config_.bounded_force_correlation.count();
  const double bounded_n = config_.bounded_aero_force_noise_per_sqrt_hz * std::abs(aero);
  const double bounded_mps = bounded_n / m_eff * std::sqrt(tau_s / 2.0);
  const Decay ripple = lumped({in.ripple_sigma_mps, phi_road}, {bounded_mps, std::exp(-dt / tau_s)});
  f(CrrState::ripple, CrrState::ripple) = ripple.phi;
  next(CrrState::ripple) = ripple.phi * x(CrrState::ripple);
  q(CrrState::ripple) = ripple.q;
  const Vec x_before = core_.x();
  const Mat p_before = core_.p();
  core_.predict(next, f, q);
  if (smoother_ != nullptr) smoother_->record_predict(x_before, p_before, f, core_.x(), q);
  ++counters_.predicts;
}

void CrrFilter::predict_to(const model::ForceInputs& in) {
  if (!started_ || in.t <= t_) return;
  // Equal sub-steps, as many as the interval holds max_step (rounded, at least one): a tick a few
  // microseconds past max_step would otherwise add a sliver of a step, which costs a whole step's
  // work and a smoother step's memory (a third of an hour's steps were such slivers).
  const std::int64_t span = (in.t - t_).count(), max = std::max<std::int64_t>(1, config_.max_step.count());
  const std::int64_t n = std::max<std::int64_t>(1, (span + max / 2) / max);
  const std::int64_t whole = span / n, rest = span % n;
  const CaptureTime from = t_;
  // A pavement change enters once over the interval, not once per sub-step.
  double jump = in.crr_jump_variance;
  for (std::int64_t i = 1; i <= n; ++i) {
    const CaptureTime to = from + Nanoseconds{whole * i + rest * i / n};
    step(to_seconds(to - t_), in, jump);
    jump = 0;
    t_ = to;
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
  zhat << core_.x()(CrrState::speed) + core_.x()(CrrState::ripple);
  r << sigma * sigma;
  Eigen::Matrix<double, 1, CrrState::count> h = Eigen::Matrix<double, 1, CrrState::count>::Zero();
  h(0, CrrState::speed) = 1.0;
  h(0, CrrState::ripple) = 1.0;
  const ekf::UpdateResult res = core_.update<1>(z, zhat, h, r, config_.gate_nis);
  if (res.accepted) {
    ++counters_.updates;
    counters_.nis_sum += res.nis;
  } else {
    ++counters_.outliers;
  }
  return res;
}

}  // namespace roadload
