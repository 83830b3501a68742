#pragma once
// The plant's own constants, shared by its files (plant.cpp, plant_step.cpp): the driver's shift
// rule, the engine's response and the geometry the tires read the road with.
#include <numbers>

namespace roadload::sim::plant_detail {

constexpr double kRadps_per_rpm = 2.0 * std::numbers::pi / 60.0;
constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kSlopeBase_m = 0.05;  // half-width of the slope difference under a tire
constexpr double kTorqueLag_s = 0.1;   // fuelling and turbo response
constexpr double kGovernorTau_s = 0.3;
constexpr double kUpshift_rpm = 1650.0, kDownshift_rpm = 900.0, kMinCruise_rpm = 1000.0;
constexpr double kBrakeMargin_mps = 1.5;  // overspeed before the cruise control uses the service brake

}  // namespace roadload::sim::plant_detail
