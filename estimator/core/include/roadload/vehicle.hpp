#pragma once
// One truck as every layer sees it: the estimator takes its force balance and axles from it, the
// simulator builds its plant from it, roadloadd and the gap diagnosis place sensors with it. The
// values come from a vehicle file (config/vehicles/, drivers' vehicle_file.hpp), each with its
// source there; no particular truck's numbers live in code.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/time.hpp"

namespace roadload {

// A quarter car's suspension and tires (both sides of the axle together).
struct AxleSuspension {
  double spring_npm = 0;
  double damper_nspm = 0;
  double tire_stiffness_npm = 0;  // all the axle's tires
  double tire_damping_nspm = 0;
};

struct VehicleAxle {
  std::string name;               // "front", "drive1", ...: meta.toml's vehicle.<name>_load_kg
  std::string unit;               // "tractor", "trailer": a frame accelerometer serves its own unit only
  double position_m = 0;          // behind the front axle
  double load_kg = 0;             // static, on a level road
  double unsprung_kg = 0;         // axle, wheels, tires and half the suspension: Eq. 2.1's M_w
  double report_unsprung_kg = 0;  // tires and wheels only, as seed report Table 6.1 counts them
  int tires = 0;
  double tire_radius_m = 0;       // dynamic rolling radius
  double wheel_inertia_kgm2 = 0;  // all the axle's wheel ends
  bool driven = false;
  AxleSuspension suspension;
  std::string axle_mount;   // accelerometer position on the axle, without "-left"/"-right"
  std::string frame_mount;  // on the frame above it
};

// An accelerometer the truck carries: where it sits and what it can read.
struct AccelerometerMount {
  std::string name;      // as the seed report labels them (TLF1, ...)
  std::string position;  // the recording format's mount, "tractor-front-axle-left", ...
  std::string axle;      // the axle it sits on or above
  bool on_axle = false;  // unsprung (on the axle) or sprung (on the frame)
  double range_g = 0;
};

// The engine as the plant runs it; EC1 (SPN 544 and its torque map) tells the estimator the rest.
struct EngineDescription {
  double reference_torque_nm = 0;  // EC1 SPN 544; the estimator's fallback when EC1 is not heard
  double idle_rpm = 0;
  double inertia_kgm2 = 0;  // EC1 SPN 1794
  // Full-load indicated torque as a fraction of the reference at EC1's six map points.
  std::vector<double> full_load_rpm, full_load_fraction;
  // Motoring friction, a + b n + c n^2 in % of the reference, n in thousands of rpm.
  double friction_a_pct = 0, friction_b_pct = 0, friction_c_pct = 0;
  // How far one engine of the type may be from that friction, as a share of it (wear, oil, build).
  double friction_sigma = 0;
  // How far the ECU's torque (EEC1 against SPN 544) may be from the flywheel's, as a share: one
  // sigma of a scale error. J1939 states no accuracy; makers quote a few percent.
  double torque_scale_sigma = 0;
};

struct DrivelineDescription {
  std::vector<double> gear_ratios;  // first gear first
  double final_drive = 0;
  double efficiency = 0;        // one figure for every gear and load
  double efficiency_sigma = 0;  // how far one gearbox and axle of the type may be from it
  double inertia_kgm2 = 0;      // gearbox, shafts and axle gears referred to the engine
  Seconds shift_time{0};
};

// Indicated efficiency in the Willans form, and the fuel.
struct FuelDescription {
  double eta_indicated_max = 0;
  double n_opt_rpm = 0;
  double eta_speed_coeff = 0;
  double lhv_jpkg = 0;
  double density_kgpl = 0;
};

struct AccessoryDescription {
  double alternator_w = 0, steering_w = 0, compressor_w = 0;
  double fan_engaged_w = 0;  // at fan_ref_rpm; scales with the fan's speed cubed
  double fan_ref_rpm = 0;
  double fan_idle_w = 0;  // disengaged viscous drag, at fan_ref_rpm
};

// The axles' static loads summed, and their centre behind the front axle (0 without load): for
// any list of axles with load_kg and position_m (the vehicle's, the plant's).
template <typename Axles>
double total_load_kg(const Axles& axles) {
  double m = 0;
  for (const auto& a : axles) m += a.load_kg;
  return m;
}
template <typename Axles>
double load_centre_m(const Axles& axles) {
  double moment = 0;
  for (const auto& a : axles) moment += a.load_kg * a.position_m;
  const double m = total_load_kg(axles);
  return m > 0 ? moment / m : 0.0;
}

struct Vehicle {
  std::string name;
  std::string description;
  std::string vin;
  std::string source;              // the file it was read from
  std::vector<VehicleAxle> axles;  // front to rear
  std::vector<AccelerometerMount> accelerometers;
  EngineDescription engine;
  DrivelineDescription driveline;
  FuelDescription fuel;
  AccessoryDescription accessories;
  double cda_m2 = 0;        // the type's drag area: the plant's value, the estimator's prior
  double cda_sigma_m2 = 0;  // how far one truck of the type may be from it
  double gnss_antenna_behind_front_m = 0;
  double gnss_antenna_height_m = 0;
  // How well the axle loads are known: a scale ticket's 1 %, a declared cargo's 5-10 %.
  double mass_sigma_kg = 0;
  // How far the tires' rolling radius may be from the axles' tire_radius_m (brand, wear, the size
  // the ECUs were programmed with): the speedometer's error. 0 when not known.
  double tire_radius_sigma_m = 0;
  // How far one truck's tires' rolling resistance may be from the type's, as a share of it (brand,
  // model, wear): what sets one truck of a fleet apart on the same pavement. 0 when not known.
  double tire_crr_sigma = 0;

  double mass_kg() const;            // the axles' static loads
  double cg_behind_front_m() const;  // from the axle loads
  double length_m() const;           // front axle to the last
  // The first driven axle: its tires' radius turns wheel speed into engine speed.
  const VehicleAxle* drive_axle() const;
  const VehicleAxle* axle(std::string_view axle_name) const;
};

}  // namespace roadload
