#pragma once
// The MnROAD test truck of the seed report (Tables 6.1, 6.2) as the plant's parameters. Values and
// their sources: docs/simulator-parameters.md, sections 1-3.
#include <array>
#include <cstddef>
#include <string>

#include "roadload/sim/vertical.hpp"

namespace roadload::sim {

inline constexpr std::size_t kTruckAxles = 5;

struct AxleSpec {
  std::string name;          // "front", "drive1", ...
  double position_m = 0;     // behind the front axle
  double load_kg = 0;        // static axle load (S Table 6.2)
  AxleParams vertical;       // sprung share, unsprung, springs and dampers
  double tire_radius_m = 0;  // dynamic rolling radius
  double wheel_inertia_kgm2 = 0;  // all wheel ends of the axle
  bool driven = false;
};

struct EngineSpec {
  double ref_torque_nm = 2386.0;  // EC1 SPN 544 of a real engine
  double idle_rpm = 650.0;
  double inertia_kgm2 = 3.824;    // EC1 SPN 1794
  // Full-load indicated torque, fraction of the reference, at EC1's speed points.
  std::array<double, 6> full_load_rpm{650, 900, 1400, 1675, 2086, 2100};
  std::array<double, 6> full_load_fraction{0.64, 0.98, 1.00, 0.86, 0.15, 0.0};
  // Motoring friction (a + b n + c n^2) % of the reference, n in krpm.
  double friction_a = 4.0, friction_b = 2.0, friction_c = 1.0;
};

struct FuelSpec {
  double eta_indicated_max = 0.47;  // Willans form, tuned for 0.435 peak brake efficiency
  double n_opt_rpm = 1250.0;
  double eta_speed_coeff = 0.25;
  double lhv_jpkg = 42.8e6;
  double density_kgpl = 0.84;
};

struct DrivelineSpec {
  std::array<double, 10> gear_ratios{12.80, 9.25, 6.76, 4.90, 3.58, 2.61, 1.89, 1.38, 1.00, 0.73};
  double final_drive = 3.36;
  double efficiency = 0.94;        // the simple model: one figure for every gear and load
  double inertia_kgm2 = 0.5;       // gearbox, shafts and axle gears referred to the engine
  double shift_time_s = 1.5;
};

struct AccessorySpec {
  double alternator_w = 2000.0;
  double steering_w = 1000.0;
  double compressor_w = 1200.0;    // 4 kW loaded at ~15 % duty, 0.7 kW unloaded: the mean
  double fan_engaged_w = 20000.0;  // at fan_ref_rpm; scales with speed cubed
  double fan_ref_rpm = 1340.0;
  double fan_idle_w = 700.0;       // disengaged viscous drag
};

struct TruckParams {
  std::string vin = "1HSGSSJT8CJ536729";
  std::array<AxleSpec, kTruckAxles> axles;
  EngineSpec engine;
  FuelSpec fuel;
  DrivelineSpec driveline;
  AccessorySpec accessories;
  double cda_m2 = 6.2;

  double total_mass_kg() const;
  // Distance of the centre of gravity behind the front axle, from the axle loads.
  double cg_position_m() const;
};

// Unsprung masses: `physical` adds the axle and part of the suspension to tires and wheels (what a
// quarter car needs); `report` uses the report's tires-and-wheels definition of Table 6.1.
enum class UnsprungDefinition { physical, report };

TruckParams mnroad_truck(UnsprungDefinition unsprung = UnsprungDefinition::physical);

}  // namespace roadload::sim
