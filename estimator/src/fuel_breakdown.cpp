#include "roadload/fuel_breakdown.hpp"

#include <numbers>
#include <numeric>

namespace roadload {
namespace {

constexpr double kRadps_per_rpm = 2.0 * std::numbers::pi / 60.0;

}  // namespace

const char* to_string(FuelUse u) {
  switch (u) {
    case FuelUse::engine: return "engine";
    case FuelUse::driveline: return "driveline";
    case FuelUse::accessories: return "accessories";
    case FuelUse::aero: return "aero";
    case FuelUse::rolling: return "rolling";
    case FuelUse::grade: return "grade";
    case FuelUse::acceleration: return "acceleration";
    case FuelUse::braking: return "braking";
    case FuelUse::count: break;
  }
  return "?";
}

void FuelBreakdown::add(const PowerInterval& p, double energy_jpl) {
  auto& e = energy_j;
  const auto row = [&e](FuelUse u) -> double& { return e[static_cast<std::size_t>(u)]; };
  const double omega = p.engine_speed_rpm * kRadps_per_rpm;
  const double dx = 0.5 * (p.speed_from_mps + p.speed_to_mps) * p.dt_s;
  const double fuel_l_now = p.fuel_rate_lph / 3600.0 * p.dt_s;
  fuel_l += fuel_l_now;
  distance_m += dx;
  time_s += p.dt_s;

  // The wheel side needs only the smoothed resistances and the speed.
  const double kinetic_j = 0.5 * p.effective_mass_kg * (p.speed_to_mps * p.speed_to_mps - p.speed_from_mps * p.speed_from_mps);
  const double resist_j = (p.aero_n + p.rolling_n + p.grade_n) * dx;
  row(FuelUse::aero) += p.aero_n * dx;
  row(FuelUse::rolling) += p.rolling_n * dx;
  row(FuelUse::grade) += p.grade_n * dx;
  row(FuelUse::acceleration) += kinetic_j;
  const double at_wheels_j = p.attributable && p.engaged ? p.tractive_n * dx : 0.0;
  wheel_j += at_wheels_j;
  // Brakes take what the wheel work and the resistances leave of the speed change.
  const double brake_j = p.braking ? at_wheels_j - resist_j - kinetic_j : 0.0;
  row(FuelUse::braking) += brake_j;
  if (!p.attributable) {
    // The engine's torques are unknown: engine, driveline and accessories are one remainder.
    unsplit_l += fuel_l_now;
    row(FuelUse::engine) += fuel_l_now * energy_jpl - resist_j - kinetic_j - brake_j;
    return;
  }
  const double indicated_j = p.indicated_nm * omega * p.dt_s;
  const double flywheel_j = (p.indicated_nm - p.friction_nm - p.parasitic_nm) * omega * p.dt_s;
  row(FuelUse::engine) += fuel_l_now * energy_jpl - indicated_j + p.friction_nm * omega * p.dt_s;
  row(FuelUse::accessories) += p.parasitic_nm * omega * p.dt_s;
  // Declutched, the flywheel's work goes into the engine's own speed change at the shift.
  row(FuelUse::driveline) += flywheel_j - at_wheels_j;
}

double FuelBreakdown::sum_l(double energy_jpl) const { return std::accumulate(energy_j.begin(), energy_j.end(), 0.0) / energy_jpl; }

double FuelBreakdown::closure(double energy_jpl) const { return fuel_l > 0 ? (sum_l(energy_jpl) - fuel_l) / fuel_l : 0.0; }

double FuelBreakdown::unexplained_j(double energy_jpl) const { return (sum_l(energy_jpl) - fuel_l) * energy_jpl; }

}  // namespace roadload
