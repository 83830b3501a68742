#pragma once
// The plain-number keys of a vehicle file, each with the member it fills and the range that is
// physical: the reader checks them and the writer prints them from these same tables.
#include "roadload/vehicle.hpp"

namespace roadload::vehicle_fields {

template <typename T>
struct NumberField {
  const char* key;
  double T::*member;
  double lo, hi;
};

inline constexpr NumberField<Vehicle> kBody[] = {
    {"cda_m2", &Vehicle::cda_m2, 0.5, 30},
    {"cda_sigma_m2", &Vehicle::cda_sigma_m2, 0, 10},
    {"gnss_antenna_behind_front_m", &Vehicle::gnss_antenna_behind_front_m, -5, 50},
    {"gnss_antenna_height_m", &Vehicle::gnss_antenna_height_m, 0, 10},
    {"mass_sigma_kg", &Vehicle::mass_sigma_kg, 0, 100000},
};

// Keys a vehicle file may leave out (0: not known), so that files and recordings written before
// them still read.
inline constexpr NumberField<Vehicle> kBodyOptional[] = {
    {"tire_radius_sigma_m", &Vehicle::tire_radius_sigma_m, 0, 0.05},
    {"tire_crr_sigma", &Vehicle::tire_crr_sigma, 0, 0.5},
};

inline constexpr NumberField<EngineDescription> kEngine[] = {
    {"reference_torque_nm", &EngineDescription::reference_torque_nm, 1, 64255},  // SPN 544's range
    {"idle_rpm", &EngineDescription::idle_rpm, 100, 3000},
    {"inertia_kgm2", &EngineDescription::inertia_kgm2, 0, 100},
    {"friction_a_pct", &EngineDescription::friction_a_pct, 0, 100},
    {"friction_b_pct", &EngineDescription::friction_b_pct, 0, 100},
    {"friction_c_pct", &EngineDescription::friction_c_pct, 0, 100},
    {"friction_sigma", &EngineDescription::friction_sigma, 0, 1},
    {"torque_scale_sigma", &EngineDescription::torque_scale_sigma, 0, 0.5},
};

inline constexpr NumberField<DrivelineDescription> kDriveline[] = {
    {"final_drive", &DrivelineDescription::final_drive, 0.5, 20},
    {"efficiency", &DrivelineDescription::efficiency, 0.5, 1},
    {"efficiency_sigma", &DrivelineDescription::efficiency_sigma, 0, 0.2},
    {"inertia_kgm2", &DrivelineDescription::inertia_kgm2, 0, 100},
};

inline constexpr NumberField<FuelDescription> kFuel[] = {
    {"eta_indicated_max", &FuelDescription::eta_indicated_max, 0.05, 0.7},
    {"n_opt_rpm", &FuelDescription::n_opt_rpm, 100, 8000},
    {"eta_speed_coeff", &FuelDescription::eta_speed_coeff, 0, 1},
    {"lhv_jpkg", &FuelDescription::lhv_jpkg, 1e6, 1.5e8},
    {"density_kgpl", &FuelDescription::density_kgpl, 0.1, 2},
};

inline constexpr NumberField<AccessoryDescription> kAccessories[] = {
    {"alternator_w", &AccessoryDescription::alternator_w, 0, 1e5},  {"steering_w", &AccessoryDescription::steering_w, 0, 1e5},
    {"compressor_w", &AccessoryDescription::compressor_w, 0, 1e5},  {"fan_engaged_w", &AccessoryDescription::fan_engaged_w, 0, 2e5},
    {"fan_ref_rpm", &AccessoryDescription::fan_ref_rpm, 100, 8000}, {"fan_idle_w", &AccessoryDescription::fan_idle_w, 0, 1e5},
};

// An axle's numbers; its unsprung masses are checked against its load as well.
inline constexpr NumberField<VehicleAxle> kAxle[] = {
    {"position_m", &VehicleAxle::position_m, 0, 50},          {"load_kg", &VehicleAxle::load_kg, 1, 50000},
    {"unsprung_kg", &VehicleAxle::unsprung_kg, 1, 50000},     {"report_unsprung_kg", &VehicleAxle::report_unsprung_kg, 1, 50000},
    {"tire_radius_m", &VehicleAxle::tire_radius_m, 0.2, 1.0}, {"wheel_inertia_kgm2", &VehicleAxle::wheel_inertia_kgm2, 0, 1000},
};

inline constexpr NumberField<AxleSuspension> kSuspension[] = {
    {"spring_npm", &AxleSuspension::spring_npm, 1e3, 1e8},
    {"damper_nspm", &AxleSuspension::damper_nspm, 0, 1e7},
    {"tire_stiffness_npm", &AxleSuspension::tire_stiffness_npm, 1e4, 1e9},
    {"tire_damping_nspm", &AxleSuspension::tire_damping_nspm, 0, 1e7},
};

inline constexpr NumberField<AccelerometerMount> kAccelerometer[] = {
    {"range_g", &AccelerometerMount::range_g, 0.1, 1000},
};

// Ranges of the keys that are not plain numbers.
inline constexpr double kMaxTires = 8;
inline constexpr double kMaxGearRatio = 30, kMinGearRatio = 0.1;
inline constexpr double kMaxMapRpm = 8031.875;  // SPN 188's range
inline constexpr double kMaxFullLoadFraction = 1.25;
inline constexpr double kMaxShiftTime_s = 10;
inline constexpr std::size_t kMapPoints = 6;  // EC1's map: idle, four points and high idle

}  // namespace roadload::vehicle_fields
