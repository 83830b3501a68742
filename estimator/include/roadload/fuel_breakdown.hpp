#pragma once
// Where the fuel went (seed report Figures 2.2, 6.4, 6.5): the measured fuel (LFE1) split by
// the work of each force over the drive. Work converts to litres by diesel's energy content, as the
// report does; engine losses are the fuel's energy not turned into indicated work, plus friction.
// The rows therefore sum to the measured fuel exactly when the force balance closes: their sum
// minus the fuel is the closure error, reported, never hidden.
#include <array>
#include <cstddef>

namespace roadload {

// Lower heating value of US No. 2 diesel, 128,488 Btu per US gallon (Argonne GREET): 35.8 MJ/L.
inline constexpr double kDieselEnergy_jpl = 35.8e6;

enum class FuelUse : std::size_t { engine, driveline, accessories, aero, rolling, grade, acceleration, braking, count };
inline constexpr std::size_t kFuelUseCount = static_cast<std::size_t>(FuelUse::count);
const char* to_string(FuelUse u);

// One interval of a drive, with its inputs held over it. Forces oppose the motion when positive.
struct PowerInterval {
  double dt_s = 0;
  double fuel_rate_lph = 0;
  double engine_speed_rpm = 0;
  double indicated_nm = 0, friction_nm = 0, parasitic_nm = 0;  // J1939's engine torques
  bool engaged = false;                                        // the flywheel drives the wheels (not shifting, clutch closed)
  double tractive_n = 0;                                       // at the wheels, from the flywheel torque
  double speed_from_mps = 0, speed_to_mps = 0;
  double effective_mass_kg = 0;
  double aero_n = 0, rolling_n = 0, grade_n = 0;
  bool braking = false;
  // False while the engine's torques cannot be read (no EC1 yet, no EEC1, no gear): the wheel
  // side still splits by force, the rest of the fuel is booked as engine losses.
  bool attributable = true;
};

struct FuelBreakdown {
  std::array<double, kFuelUseCount> energy_j{};
  double fuel_l = 0;     // measured
  double unsplit_l = 0;  // of it, burnt while the engine's torques could not be read
  double distance_m = 0;
  double time_s = 0;
  double wheel_j = 0;  // the tractive force's work at the wheels, where the torques are known

  void add(const PowerInterval& p, double energy_jpl = kDieselEnergy_jpl);
  double energy(FuelUse u) const { return energy_j[static_cast<std::size_t>(u)]; }
  double liters(FuelUse u, double energy_jpl = kDieselEnergy_jpl) const { return energy(u) / energy_jpl; }
  double sum_l(double energy_jpl = kDieselEnergy_jpl) const;
  // (sum of the rows - measured fuel) / measured fuel.
  double closure(double energy_jpl = kDieselEnergy_jpl) const;
  // The work the force balance leaves unexplained (resistances, speed change and brakes less the
  // wheel work), J: the rows' sum less the fuel's energy.
  double unexplained_j(double energy_jpl = kDieselEnergy_jpl) const;
};

}  // namespace roadload
