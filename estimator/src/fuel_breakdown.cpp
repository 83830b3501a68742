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
  const double omega = p.engine_speed_rpm * kRadps_per_rpm;
  const double v_mean = 0.5 * (p.speed_from_mps + p.speed_to_mps);
  const double dx = v_mean * p.dt_s;
  const double fuel_l_now = p.fuel_rate_lph / 3600.0 * p.dt_s;
  fuel_l += fuel_l_now;
  distance_m += dx;
  const double indicated_j = p.indicated_nm * omega * p.dt_s;
  e[static_cast<std::size_t>(FuelUse::engine)] += fuel_l_now * energy_jpl - indicated_j + p.friction_nm * omega * p.dt_s;
  e[static_cast<std::size_t>(FuelUse::accessories)] += p.parasitic_nm * omega * p.dt_s;
  const double flywheel_j = (p.indicated_nm - p.friction_nm - p.parasitic_nm) * omega * p.dt_s;
  const double kinetic_j = 0.5 * p.effective_mass_kg * (p.speed_to_mps * p.speed_to_mps - p.speed_from_mps * p.speed_from_mps);
  const double resist_j = (p.aero_n + p.rolling_n + p.grade_n) * dx;
  e[static_cast<std::size_t>(FuelUse::aero)] += p.aero_n * dx;
  e[static_cast<std::size_t>(FuelUse::rolling)] += p.rolling_n * dx;
  e[static_cast<std::size_t>(FuelUse::grade)] += p.grade_n * dx;
  e[static_cast<std::size_t>(FuelUse::acceleration)] += kinetic_j;
  if (p.engaged) {
    e[static_cast<std::size_t>(FuelUse::driveline)] += flywheel_j - p.tractive_n * dx;
  } else {
    // Declutched, the flywheel's work goes into the engine's own speed change at the shift.
    e[static_cast<std::size_t>(FuelUse::driveline)] += flywheel_j;
  }
  // Brakes take what the wheel work and the resistances leave of the speed change.
  if (p.braking) {
    const double wheel_j = p.engaged ? p.tractive_n * dx : 0.0;
    e[static_cast<std::size_t>(FuelUse::braking)] += wheel_j - resist_j - kinetic_j;
  }
}

double FuelBreakdown::sum_l(double energy_jpl) const {
  return std::accumulate(energy_j.begin(), energy_j.end(), 0.0) / energy_jpl;
}

double FuelBreakdown::closure(double energy_jpl) const {
  return fuel_l > 0 ? (sum_l(energy_jpl) - fuel_l) / fuel_l : 0.0;
}

}  // namespace roadload
