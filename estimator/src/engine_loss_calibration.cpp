#include "roadload/engine_loss_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace roadload {

void EngineLossCalibration::push(const EngineReading& r) {
  const bool continues = open_ && r.standing && std::abs(r.rpm - anchor_rpm_) <= config_.steady_band_rpm &&
                         to_seconds(r.t - last_) <= config_.max_gap.count();
  if (!continues) {
    close_hold();
    if (!r.standing) return;
    open_ = true;
    anchor_rpm_ = r.rpm;
    resolution_nm_ = 0;
    start_ = r.t;
    rpm_ = torque_ = eec3_ = eec3_friction_ = RunningStats{};
    tail_.clear();
  }
  last_ = r.t;
  if (to_seconds(r.t - start_) < config_.settle.count()) return;
  // A reading counts once the hold has gone on `tail` past it: the engine accelerating toward the
  // next speed (its inertia torque, 75 N m for 50 rpm in 0.3 s) stays in the tail when it ends.
  tail_.push_back(r);
  while (to_seconds(r.t - tail_.front().t) > config_.tail.count()) {
    keep(tail_.front());
    tail_.pop_front();
  }
}

void EngineLossCalibration::keep(const EngineReading& r) {
  if (rpm_.n == 0) first_kept_ = r.t;
  last_kept_ = r.t;
  rpm_.add(r.rpm);
  torque_.add(r.indicated_nm);
  eec3_.add(r.eec3_loss_nm);
  eec3_friction_.add(r.eec3_friction_nm);
  resolution_nm_ = std::max(resolution_nm_, r.resolution_nm);
}

void EngineLossCalibration::close_hold() {
  if (!open_) return;
  open_ = false;
  const double kept_s = to_seconds(last_kept_ - first_kept_);
  if (rpm_.n < 2 || kept_s < config_.min_hold.count()) return;
  // A steady engine reports one value for seconds: its scatter says nothing of the rounding, a
  // uniform error of one resolution step, which bounds the point's error from below.
  const double rounding_nm = resolution_nm_ / std::sqrt(12.0);
  const double scatter_nm = torque_.std() / std::sqrt(static_cast<double>(torque_.n));
  EngineLossHold h;
  h.point = {rpm_.mean, torque_.mean, std::hypot(rounding_nm, scatter_nm)};
  h.eec3_loss_nm = eec3_.mean;
  h.eec3_friction_nm = eec3_friction_.mean;
  h.duration_s = kept_s;
  h.samples = torque_.n;
  holds_.push_back(h);
}

std::vector<EngineLossHold> EngineLossCalibration::finish() {
  close_hold();
  std::vector<EngineLossHold> out = holds_;
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.point.rpm < b.point.rpm; });
  // Two holds at one speed (a calibration run twice) are one point, weighted by their samples.
  std::vector<EngineLossHold> merged;
  for (const EngineLossHold& h : out) {
    if (!merged.empty() && h.point.rpm - merged.back().point.rpm <= config_.steady_band_rpm) {
      EngineLossHold& m = merged.back();
      const double wa = static_cast<double>(m.samples), wb = static_cast<double>(h.samples), w = wa + wb;
      m.point.rpm = (wa * m.point.rpm + wb * h.point.rpm) / w;
      m.point.loss_nm = (wa * m.point.loss_nm + wb * h.point.loss_nm) / w;
      m.point.sigma_nm = std::max(m.point.sigma_nm, h.point.sigma_nm);
      m.eec3_loss_nm = (wa * m.eec3_loss_nm + wb * h.eec3_loss_nm) / w;
      m.eec3_friction_nm = (wa * m.eec3_friction_nm + wb * h.eec3_friction_nm) / w;
      m.duration_s += h.duration_s;
      m.samples += h.samples;
    } else {
      merged.push_back(h);
    }
  }
  if (const auto curve = fit_friction_curve(merged)) split_losses(*curve, merged);
  return merged;
}

namespace {

constexpr double kAccessorySmoothing_rpm = 150;

// The accessories at `i`: the loss less the friction curve, a straight line fitted over the holds
// within kAccessorySmoothing_rpm.
double smoothed_accessories_nm(const FrictionCurve& curve, const std::vector<EngineLossHold>& holds, std::size_t i) {
  const double at = holds[i].point.rpm;
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const EngineLossHold& h : holds) {
    const double x = h.point.rpm - at;
    if (std::abs(x) > kAccessorySmoothing_rpm) continue;
    const double y = h.point.loss_nm - curve.at(h.point.rpm);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double det = n * sxx - sx * sx;
  return det > 0 ? (sxx * sy - sx * sxy) / det : sy / n;
}

}  // namespace

void split_losses(const FrictionCurve& curve, std::vector<EngineLossHold>& holds) {
  std::vector<double> accessories(holds.size());
  for (std::size_t i = 0; i < holds.size(); ++i) accessories[i] = smoothed_accessories_nm(curve, holds, i);
  for (std::size_t i = 0; i < holds.size(); ++i) holds[i].point.friction_nm = holds[i].point.loss_nm - accessories[i];
}

double FrictionCurve::at(double rpm) const {
  const double k = rpm / 1000.0;
  return a_nm + k * (b_nm_per_krpm + k * c_nm_per_krpm2);
}

std::optional<FrictionCurve> fit_friction_curve(const std::vector<EngineLossHold>& holds) {
  constexpr std::size_t kTerms = 3;
  std::vector<double> krpm, value;
  for (std::size_t i = 1; i < holds.size(); ++i) {
    const EngineLossHold& lo = holds[i - 1];
    const EngineLossHold& hi = holds[i];
    if (std::abs(hi.eec3_friction_nm - lo.eec3_friction_nm) <= 1e-9 * std::abs(lo.eec3_friction_nm)) continue;
    krpm.push_back((lo.point.rpm + hi.point.rpm) / 2000.0);
    value.push_back((lo.eec3_friction_nm + hi.eec3_friction_nm) / 2.0);
  }
  if (krpm.size() < kTerms) return std::nullopt;
  Eigen::MatrixXd a(krpm.size(), kTerms);
  Eigen::VectorXd b(krpm.size());
  for (std::size_t i = 0; i < krpm.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    a(r, 0) = 1.0;
    a(r, 1) = krpm[i];
    a(r, 2) = krpm[i] * krpm[i];
    b(r) = value[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);
  return FrictionCurve{c(0), c(1), c(2), krpm.size()};
}

EngineLossFrames::EngineLossFrames(const j1939::Database& db, EngineLossCalibrationConfig config)
    : signals_(db), eec1_(db.find_name("EEC1")), max_speed_mps_(config.max_speed_mps), calibration_(config) {}

void EngineLossFrames::push(const CanFrame& frame) {
  const auto m = assembler_.push(frame);
  if (!m) return;
  signals_.push(*m);
  if (eec1_ == nullptr || m->pgn != eec1_->pgn) return;
  const Reading& rpm = signals_.get(Quantity::engine_speed_rpm);
  const Reading& torque = signals_.get(Quantity::actual_torque_pct);
  const Reading& ref = signals_.get(Quantity::reference_torque_nm);
  if (!rpm.seen || !torque.seen) return;
  ++readings;
  if (!ref.seen) {
    ++no_reference;
    return;
  }
  const Reading& wheel = signals_.get(Quantity::wheel_speed_mps);
  const Reading& gear = signals_.get(Quantity::current_gear);
  const Reading& engaged = signals_.get(Quantity::driveline_engaged);
  const bool neutral = (gear.seen && gear.value == 0) || (engaged.seen && engaged.value < 0.5);
  EngineReading r;
  r.t = m->t;
  r.rpm = rpm.value;
  r.standing = wheel.seen && wheel.value < max_speed_mps_ && neutral;
  if (r.standing) ++standing;
  const Reading& friction = signals_.get(Quantity::friction_torque_pct);
  const Reading& parasitic = signals_.get(Quantity::parasitic_torque_pct);
  const double eec3_pct = (friction.seen ? friction.value : 0.0) + (parasitic.seen ? parasitic.value : 0.0);
  const double to_nm = ref.value / 100.0;
  r.indicated_nm = torque.value * to_nm;
  r.eec3_loss_nm = eec3_pct * to_nm;
  r.eec3_friction_nm = (friction.seen ? friction.value : 0.0) * to_nm;
  whole_percent = whole_percent || !signals_.torque_fraction_seen();
  r.resolution_nm = (signals_.torque_fraction_seen() ? 0.125 : 1.0) * to_nm;
  calibration_.push(r);
}

model::EngineLossMap engine_loss_map(const std::vector<EngineLossHold>& holds) {
  model::EngineLossMap map;
  for (const EngineLossHold& h : holds) map.add(h.point);
  return map;
}

}  // namespace roadload
