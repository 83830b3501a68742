#include "roadload/vehicle.hpp"

#include <algorithm>

namespace roadload {

double Vehicle::mass_kg() const {
  double m = 0;
  for (const VehicleAxle& a : axles) m += a.load_kg;
  return m;
}

double Vehicle::cg_behind_front_m() const {
  double moment = 0;
  for (const VehicleAxle& a : axles) moment += a.load_kg * a.position_m;
  const double m = mass_kg();
  return m > 0 ? moment / m : 0.0;
}

double Vehicle::length_m() const {
  double len = 0;
  for (const VehicleAxle& a : axles) len = std::max(len, a.position_m);
  return len;
}

const VehicleAxle* Vehicle::drive_axle() const {
  for (const VehicleAxle& a : axles) {
    if (a.driven) return &a;
  }
  return nullptr;
}

const VehicleAxle* Vehicle::axle(std::string_view axle_name) const {
  for (const VehicleAxle& a : axles) {
    if (a.name == axle_name) return &a;
  }
  return nullptr;
}

}  // namespace roadload
