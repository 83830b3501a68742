#pragma once
// The real-time CRR filter: a fixed-size EKF over [speed, CRR, CdA, torque bias, grade error,
// ripple, torque scale, efficiency scale, mass scale] driven by the force balance (model/longitudinal.hpp) and corrected by measured
// speed. Push API in capture time; no I/O and no heap after construction. CRR, CdA, a flywheel torque bias and the grade's error are
// confounded at one steady speed in one gear: the last three carry priors (config, and the grade profile's sigma along the road), and
// the filter reports CRR as identified only when its posterior is tight enough.
#include <cstdint>
#include <optional>

#include "roadload/ekf/kalman.hpp"
#include "roadload/ekf/rts.hpp"
#include "roadload/model/longitudinal.hpp"
#include "roadload/time.hpp"

namespace roadload {

// Named state indices; the size is fixed at compile time.
struct CrrState {
  // ripple: the speed the road's roughness lends and takes back (road_roughness.hpp), with the
  // force errors that integrate to nothing; the wheel speed is speed + ripple.
  // torque_scale, efficiency_scale, mass_scale: share errors of the ECU's indicated torque, the
  // driveline's efficiency and the mass, constant over a drive, only considered: their priors'
  // uncertainty widens every interval they move.
  enum Index : int {
    speed = 0,
    crr = 1,
    cda = 2,
    torque_bias = 3,
    grade_error = 4,
    ripple = 5,
    torque_scale = 6,
    efficiency_scale = 7,
    mass_scale = 8,
    count = 9
  };
};
static_assert(CrrState::count == 9, "CrrFilter matrices are sized by CrrState::count");

// One whole-percent step of EEC3's friction (SPN 514) and parasitic (SPN 2978) torque each, as
// uniform rounding errors: the flywheel torque the J1939 signals cannot resolve.
double eec3_quantization_sigma_nm(double reference_torque_nm);

struct CrrFilterConfig {
  model::TruckModel truck;
  // Error of the force balance, white, N per sqrt(Hz): a floor (torque resolution, driveline) and a
  // share of the aero drag (gusts scale with it). Both set so that the mean NIS is near 1 on the
  // simulated Mainline (30 mph) and highways (55 mph) with the roughness ripple as its own state;
  // docs/estimator.md, "Noise".
  double force_noise_n = 8;
  double aero_force_noise_per_sqrt_hz = 0.010;
  // Force errors whose time integral stays bounded: a torque sampled before or after the speed it
  // meets, the torque changing between EEC1 frames. At a tick they look like white force noise of
  // this density (a share of the aero drag, as the speed sets how fast the road changes the
  // torque); over a trip they move the speed, not the energy. They ride on the ripple state as a
  // speed offset correlated over `bounded_force_correlation`. The split from the white share is
  // sized with CdA and the engine's losses known (docs/estimator.md, "Noise").
  double bounded_aero_force_noise_per_sqrt_hz = 0.0173;
  Seconds bounded_force_correlation{5.0};
  double unusable_force_noise_n = 20000.0;  // while braking or shifting: speed follows the measurements
  double crr_walk_per_sqrt_s = 3e-4;        // CRR changes from pavement to pavement (no cells known)
  double cda_walk_per_sqrt_s = 1e-4;
  // Prior until EC1 tells the engine's reference torque: EEC3's rounding at the vehicle's
  // (analyzer_config() sets it).
  double torque_bias_sigma_nm = 0;
  double torque_bias_walk_nm_per_sqrt_s = 0.01;
  // The torque scale's value, held for the whole drive (a considered state is never updated): 0,
  // or a prior sigma off for the second run of a consider analysis (torque_scale_consider.hpp).
  double torque_scale_held = 0;
  // Estimate CdA from the data (drives across speeds) or only consider its prior's uncertainty
  // (one steady speed, where speed ripples would pull it onto any speed-correlated model error).
  // The torque bias is always only considered: one gear cannot tell it from CRR.
  bool estimate_cda = true;
  // Estimate the mass's share error from the drive: the road's grade changes the force by m g
  // sin(grade), the rolling resistance by far less, so hills tell the mass from the CRR. On flat
  // roads it stays near its prior and only widens the intervals, as a considered state would.
  bool estimate_mass = true;
  // The grade's error is estimated, within its prior: a first-order Gauss-Markov process along
  // the road, its sigma the grade profile's at each place, its correlation the profile's
  // (GradeProfile::error_correlation_m: measured from the passes, or bounded by the slope's base).
  double grade_error_correlation_m = 25.0;
  double gate_nis = 15.13;  // chi-square(1) at 0.9999: beyond it a speed is an outlier
  Nanoseconds max_step{100'000'000};
  Nanoseconds late_window{500'000'000};  // older measurements are counted and dropped
  double identified_crr_sigma = 0.0008;  // above this the CRR is reported as not identified
};

struct CrrCounters {
  std::uint64_t predicts = 0, unusable_predicts = 0, updates = 0, outliers = 0, late_used = 0, late_dropped = 0;
  double nis_sum = 0;  // over accepted updates: its mean is 1 when the noise model is right
  double mean_nis() const { return updates > 0 ? nis_sum / static_cast<double>(updates) : 0.0; }
};

class CrrFilter {
 public:
  using Core = ekf::KalmanCore<CrrState::count>;
  using Vec = Core::Vec;
  using Mat = Core::Mat;

  explicit CrrFilter(const CrrFilterConfig& config) : config_(config) {}

  // The torque-bias prior defaults to the config's; the caller may know the engine's better.
  void start(CaptureTime t, double speed_mps, std::optional<double> torque_bias_sigma_nm = std::nullopt);
  // Advances to inputs.t with the inputs held over the interval, in equal sub-steps of about max_step.
  void predict_to(const model::ForceInputs& inputs);
  // A speed measurement (wheel-based or GNSS) with its standard deviation.
  ekf::UpdateResult update_speed(CaptureTime t, double speed_mps, double sigma_mps);

  // Offline: every prediction is recorded for a fixed-interval smoother.
  void attach(ekf::RtsSmoother<CrrState::count>* smoother) { smoother_ = smoother; }

  CaptureTime time() const { return t_; }
  double speed_mps() const { return core_.x()(CrrState::speed); }
  double crr() const { return core_.x()(CrrState::crr); }
  double crr_sigma() const;
  double cda_m2() const { return core_.x()(CrrState::cda); }
  double mass_kg() const { return config_.truck.mass_kg * (1.0 + core_.x()(CrrState::mass_scale)); }
  double mass_sigma_kg() const;
  double torque_bias_nm() const { return core_.x()(CrrState::torque_bias); }
  bool crr_identified() const { return crr_sigma() <= config_.identified_crr_sigma; }
  const Core& core() const { return core_; }
  const CrrCounters& counters() const { return counters_; }
  const CrrFilterConfig& config() const { return config_; }
  // The grade profile's own error correlation (GradeProfile::error_correlation_m), once it is known.
  void set_grade_error_correlation_m(double m) { config_.grade_error_correlation_m = m; }

 private:
  void step(double dt_s, const model::ForceInputs& in, double crr_jump_variance);

  CrrFilterConfig config_;
  Core core_;
  CaptureTime t_{};
  bool started_ = false;
  CrrCounters counters_;
  ekf::RtsSmoother<CrrState::count>* smoother_ = nullptr;
};

}  // namespace roadload
