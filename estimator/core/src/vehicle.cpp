#include "roadload/vehicle.hpp"

#include <algorithm>

namespace roadload {

double Vehicle::mass_kg() const { return total_load_kg(axles); }

double Vehicle::cg_behind_front_m() const { return load_centre_m(axles); }

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
