#pragma once
// Vertical dynamics: one quarter car per axle (both sides lumped), driven by the road height under
// the tire. Coordinates are deviations from static equilibrium; gravity appears only as the static
// tire load W = (m_s + m_u) g, which bounds the dynamic tire force from below (lift-off).
// Energy is ledgered alongside the state, inside the same RK4 step, so that
// road work = dissipation + change of stored energy closes to integrator precision: ~1e-8 relative
// in contact at 1/2400 s; ~1e-4 over a lift-off, whose contact switch costs RK4 its order.
#include <array>
#include <cstddef>
#include <span>

namespace roadload::sim {

inline constexpr std::size_t kMaxAxles = 8;

struct AxleParams {
  double sprung_kg = 0, unsprung_kg = 0, k_susp_npm = 0, c_susp_nspm = 0, k_tire_npm = 0, c_tire_nspm = 0, coulomb_n = 0;
};

struct AxleOutputs {             // at the end of the last step
  double tire_force_n = 0;       // total vertical tire force incl. static load, >= 0
  double sprung_accel_mps2 = 0;  // absolute vertical acceleration of the sprung mass (no g)
  double unsprung_accel_mps2 = 0;
  double sprung_z_m = 0, unsprung_z_m = 0, sprung_v_mps = 0, unsprung_v_mps = 0;
  double damper_power_w = 0;  // c_s v_rel^2
  double friction_power_w = 0;
  // c_t (zdot_u - zdot_r)^2 while the tire is in contact. In lift-off it is the power the tire
  // absorbs beyond its spring (0 once the spring is unloaded), so energy still closes.
  double tire_power_w = 0;
};

struct AxleEnergy {
  double road_work_j = 0, damper_j = 0, friction_j = 0, tire_j = 0;
};

class VerticalModel {
 public:
  // At most kMaxAxles; further axles are ignored (axle_count() tells how many were taken).
  explicit VerticalModel(std::span<const AxleParams> axles);

  // Starts at static equilibrium on road heights `road_z_m` (one per axle) and clears the energies.
  void reset(std::span<const double> road_z_m);
  // The road height moves linearly from start to end over the step; the caller has applied the
  // wheelbase delay and tire enveloping. dt_s > 0.
  void step(double dt_s, std::span<const double> road_z_start_m, std::span<const double> road_z_end_m);

  std::size_t axle_count() const { return count_; }
  const AxleOutputs& outputs(std::size_t axle) const { return out_[axle]; }
  const AxleEnergy& energy(std::size_t axle) const { return energy_[axle]; }  // since reset
  // Kinetic energy of both masses plus the springs' energy in deviation coordinates.
  double stored_energy_j(std::size_t axle) const;

  // Keeps the state in deviation coordinates, so a slow change (tire stiffness with pressure)
  // moves the equilibrium without a transient.
  void set_params(std::size_t axle, const AxleParams& p) { params_[axle] = p; }

 private:
  std::array<AxleParams, kMaxAxles> params_{};
  std::array<std::array<double, 4>, kMaxAxles> state_{};  // z_s, v_s, z_u, v_u
  std::array<double, kMaxAxles> road_z_m_{};              // at the end of the last step
  std::array<AxleOutputs, kMaxAxles> out_{};
  std::array<AxleEnergy, kMaxAxles> energy_{};
  std::size_t count_ = 0;
};

// Analytic displacement transmissibility |Z_s/Z_r|(f) of one axle (no Coulomb friction).
double quarter_car_gain(const AxleParams& p, double freq_hz);

}  // namespace roadload::sim
