#pragma once
// Physical constants and the report's customary units, converted once.
namespace roadload::sim {

inline constexpr double kGravity_mps2 = 9.80665;
inline constexpr double kMps_per_mph = 0.44704;
inline constexpr double kM_per_ft = 0.3048;
inline constexpr double kAirGasConstant_jpkgk = 287.05;
inline constexpr double kZeroCelsius_k = 273.15;

}  // namespace roadload::sim
