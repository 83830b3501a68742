#include "roadload/sim/vertical.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "roadload/sim/units.hpp"

namespace roadload::sim {
namespace {

// Width of the tanh that stands in for sign(v_rel): below it the suspension acts as a stiff
// viscous damper (F_c / 5 mm/s), which is the "locked" leaf without an event-driven stick state.
// That damper is the stiffest term: at 1/2400 s RK4 stays stable up to F_c ~ 13 kN on the front
// axle (421 kg), four times the top of the blind-test range.
constexpr double kFrictionVelocity_mps = 0.005;

// Motion states, then the energy taken in or dissipated during the current step.
using Vec = std::array<double, 8>;

double static_load_n(const AxleParams& p) { return (p.sprung_kg + p.unsprung_kg) * kGravity_mps2; }

// The tire spring cannot pull: extended past its static deflection it is unloaded, which in
// deviation coordinates is a constant -W. Its energy is the integral of this force, so a wheel in
// the air stores its height as the spring's energy and energy still closes.
double tire_spring_force_n(const AxleParams& p, double deflection_m) {
  return std::max(p.k_tire_npm * deflection_m, -static_load_n(p));
}

double tire_spring_energy_j(const AxleParams& p, double deflection_m) {
  const double w = static_load_n(p);
  if (p.k_tire_npm * deflection_m >= -w) return 0.5 * p.k_tire_npm * deflection_m * deflection_m;
  return -w * deflection_m - 0.5 * w * w / p.k_tire_npm;
}

struct Forces {
  double susp_n;      // pushes the masses apart when compressed (acts up on m_u, down on m_s)
  double friction_n;  // part of susp_n
  double tire_n;      // dynamic tire force, >= -W
};

Forces forces(const AxleParams& p, const Vec& x, double road_z_m, double road_v_mps) {
  const double rel_v = x[1] - x[3];
  // Most axles have no friction; tanh is the dearest call of a run.
  const double friction = p.coulomb_n != 0.0 ? p.coulomb_n * std::tanh(rel_v / kFrictionVelocity_mps) : 0.0;
  const double susp = p.k_susp_npm * (x[0] - x[2]) + p.c_susp_nspm * rel_v + friction;
  const double tire = p.k_tire_npm * (road_z_m - x[2]) + p.c_tire_nspm * (road_v_mps - x[3]);
  return {susp, friction, std::max(tire, -static_load_n(p))};
}

// The state's rates under the forces `f` that forces() gave for the same state and road.
Vec rates(const AxleParams& p, const Vec& x, const Forces& f, double road_z_m, double road_v_mps) {
  const double rel_v = x[1] - x[3];
  const double tire_rate = road_v_mps - x[3];
  // Whatever the tire force carries beyond its spring is dissipated: c_t v^2 in contact, and
  // during lift-off the part of the spring's force the clamp takes away.
  const double tire_loss_n = f.tire_n - tire_spring_force_n(p, road_z_m - x[2]);
  return {x[1],
          -f.susp_n / p.sprung_kg,
          x[3],
          (f.susp_n + f.tire_n) / p.unsprung_kg,
          f.tire_n * road_v_mps,
          p.c_susp_nspm * rel_v * rel_v,
          f.friction_n * rel_v,
          tire_loss_n * tire_rate};
}

Vec rates(const AxleParams& p, const Vec& x, double road_z_m, double road_v_mps) {
  return rates(p, x, forces(p, x, road_z_m, road_v_mps), road_z_m, road_v_mps);
}

Vec axpy(const Vec& x, double a, const Vec& k) {
  Vec y;
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = x[i] + a * k[i];
  return y;
}

}  // namespace

VerticalModel::VerticalModel(std::span<const AxleParams> axles) : count_(std::min(axles.size(), kMaxAxles)) {
  std::copy_n(axles.begin(), count_, params_.begin());
  reset(road_z_m_);
}

void VerticalModel::reset(std::span<const double> road_z_m) {
  for (std::size_t i = 0; i < count_; ++i) {
    const double z = road_z_m[i];
    state_[i] = {z, 0.0, z, 0.0};
    road_z_m_[i] = z;
    energy_[i] = {};
    out_[i] = {};
    out_[i].tire_force_n = static_load_n(params_[i]);
    out_[i].sprung_z_m = z;
    out_[i].unsprung_z_m = z;
  }
}

void VerticalModel::step(double dt_s, std::span<const double> road_z_start_m, std::span<const double> road_z_end_m) {
  for (std::size_t i = 0; i < count_; ++i) {
    const AxleParams& p = params_[i];
    const double z0 = road_z_start_m[i];
    const double v = (road_z_end_m[i] - z0) / dt_s;
    const double h = dt_s;
    const Vec x{state_[i][0], state_[i][1], state_[i][2], state_[i][3], 0, 0, 0, 0};
    const Vec k1 = rates(p, x, z0, v);
    const Vec k2 = rates(p, axpy(x, 0.5 * h, k1), z0 + 0.5 * h * v, v);
    const Vec k3 = rates(p, axpy(x, 0.5 * h, k2), z0 + 0.5 * h * v, v);
    const Vec k4 = rates(p, axpy(x, h, k3), road_z_end_m[i], v);
    Vec y;
    for (std::size_t j = 0; j < y.size(); ++j) y[j] = x[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);

    state_[i] = {y[0], y[1], y[2], y[3]};
    road_z_m_[i] = road_z_end_m[i];
    AxleEnergy& e = energy_[i];
    e.road_work_j += y[4];
    e.damper_j += y[5];
    e.friction_j += y[6];
    e.tire_j += y[7];

    const Forces f = forces(p, y, road_z_end_m[i], v);
    const Vec r = rates(p, y, f, road_z_end_m[i], v);
    out_[i] = {.tire_force_n = static_load_n(p) + f.tire_n,
               .sprung_accel_mps2 = r[1],
               .unsprung_accel_mps2 = r[3],
               .sprung_z_m = y[0],
               .unsprung_z_m = y[2],
               .sprung_v_mps = y[1],
               .unsprung_v_mps = y[3],
               .damper_power_w = r[5],
               .friction_power_w = r[6],
               .tire_power_w = r[7]};
  }
}

double VerticalModel::stored_energy_j(std::size_t axle) const {
  const AxleParams& p = params_[axle];
  const auto& x = state_[axle];
  const double rel = x[0] - x[2];
  return 0.5 * (p.sprung_kg * x[1] * x[1] + p.unsprung_kg * x[3] * x[3] + p.k_susp_npm * rel * rel) +
         tire_spring_energy_j(p, road_z_m_[axle] - x[2]);
}

double quarter_car_gain(const AxleParams& p, double freq_hz) {
  const std::complex<double> s{0.0, 2.0 * std::numbers::pi * freq_hz};
  const auto susp = p.c_susp_nspm * s + p.k_susp_npm;
  const auto tire = p.c_tire_nspm * s + p.k_tire_npm;
  const auto den = (p.sprung_kg * s * s + susp) * (p.unsprung_kg * s * s + susp + tire) - susp * susp;
  return std::abs(susp * tire / den);
}

}  // namespace roadload::sim
