#include "roadload/sim/powertrain.hpp"

#include <algorithm>
#include <cmath>

namespace roadload::sim {

double full_load_indicated_torque_nm(const EngineSpec& e, double rpm) {
  const auto& n = e.full_load_rpm;
  const auto& f = e.full_load_fraction;
  if (rpm <= n.front()) return f.front() * e.reference_torque_nm;
  for (std::size_t i = 1; i < n.size(); ++i) {
    if (rpm <= n[i]) {
      const double w = (rpm - n[i - 1]) / (n[i] - n[i - 1]);
      return (f[i - 1] + w * (f[i] - f[i - 1])) * e.reference_torque_nm;
    }
  }
  return 0.0;
}

double friction_torque_nm(const EngineSpec& e, double rpm) {
  const double k = rpm / 1000.0;
  return (e.friction_a_pct + e.friction_b_pct * k + e.friction_c_pct * k * k) / 100.0 * e.reference_torque_nm;
}

double indicated_efficiency(const FuelSpec& f, double rpm) {
  const double d = (rpm - f.n_opt_rpm) / f.n_opt_rpm;
  return f.eta_indicated_max * (1.0 - f.eta_speed_coeff * d * d);
}

double fuel_rate_kgps(const FuelSpec& f, double indicated_power_w, double rpm) {
  if (indicated_power_w <= 0.0) return 0.0;  // fuel cut while motoring
  return indicated_power_w / indicated_efficiency(f, rpm) / f.lhv_jpkg;
}

double fuel_rate_lph(const FuelSpec& f, double fuel_kgps) { return fuel_kgps / f.density_kgpl * 3600.0; }

double total_ratio(const DrivelineSpec& d, int gear) {
  if (gear < 1 || gear > static_cast<int>(d.gear_ratios.size())) return 0.0;
  return d.gear_ratios[static_cast<std::size_t>(gear - 1)] * d.final_drive;
}

DrivelineLoss driveline_loss(const DrivelineSpec& d, int gear, bool detailed, double spin_scale) {
  if (!detailed) return {d.efficiency, 0.0};
  // Direct drive has no countershaft mesh; indirect gears two meshes. Hypoid axle 0.96.
  const bool direct = gear >= 1 && std::abs(d.gear_ratios[static_cast<std::size_t>(gear - 1)] - 1.0) < 1e-9;
  const double eta = (direct ? 0.985 : 0.97) * 0.96;
  // Churning: 15 N m at the gearbox input and 25 N m at the pinion, referred to the wheels.
  const double ratio = total_ratio(d, gear);
  const double spin = spin_scale * (15.0 * ratio + 25.0 * d.final_drive);
  return {eta, spin};
}

double wheel_torque_nm(const DrivelineSpec& d, const DrivelineLoss& loss, int gear, double clutch_torque_nm) {
  const double ideal = clutch_torque_nm * total_ratio(d, gear);
  // Driving: the wheels get eta of the power; motoring: the engine absorbs eta of the wheels' power.
  const double meshed = ideal >= 0.0 ? ideal * loss.efficiency : ideal / loss.efficiency;
  return meshed - loss.spin_wheel_nm;
}

double clutch_torque_for_wheel_nm(const DrivelineSpec& d, const DrivelineLoss& loss, int gear, double wheel_torque_nm) {
  const double ratio = total_ratio(d, gear);
  if (ratio <= 0.0) return 0.0;
  const double meshed = wheel_torque_nm + loss.spin_wheel_nm;
  return meshed >= 0.0 ? meshed / loss.efficiency / ratio : meshed * loss.efficiency / ratio;
}

}  // namespace roadload::sim
