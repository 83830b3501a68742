#include "roadload/sim/truck.hpp"

namespace roadload::sim {

double TruckParams::total_mass_kg() const { return total_load_kg(axles); }

double TruckParams::cg_position_m() const { return load_centre_m(axles); }

double TruckParams::drive_radius_m() const {
  for (const auto& a : axles) {
    if (a.driven) return a.tire_radius_m;
  }
  return axles.front().tire_radius_m;
}

std::size_t TruckParams::axle_index(const std::string& name) const {
  for (std::size_t i = 0; i < axles.size(); ++i) {
    if (axles[i].name == name) return i;
  }
  return axles.size();
}

TruckParams truck_from_vehicle(const Vehicle& v, UnsprungDefinition unsprung) {
  TruckParams t;
  t.vin = v.vin;
  t.description = v.description;
  for (const VehicleAxle& va : v.axles) {
    if (t.axles.size() == kMaxAxles) break;
    AxleSpec a;
    a.name = va.name;
    a.position_m = va.position_m;
    a.load_kg = va.load_kg;
    const double unsprung_kg = unsprung == UnsprungDefinition::report ? va.report_unsprung_kg : va.unsprung_kg;
    a.vertical.sprung_kg = va.load_kg - unsprung_kg;
    a.vertical.unsprung_kg = unsprung_kg;
    a.vertical.k_susp_npm = va.suspension.spring_npm;
    a.vertical.c_susp_nspm = va.suspension.damper_nspm;
    a.vertical.k_tire_npm = va.suspension.tire_stiffness_npm;
    a.vertical.c_tire_nspm = va.suspension.tire_damping_nspm;
    a.tire_radius_m = va.tire_radius_m;
    a.wheel_inertia_kgm2 = va.wheel_inertia_kgm2;
    a.driven = va.driven;
    t.axles.push_back(a);
  }
  t.engine = v.engine;
  t.fuel = v.fuel;
  t.driveline = v.driveline;
  t.accessories = v.accessories;
  t.cda_m2 = v.cda_m2;
  t.gnss_antenna_behind_front_m = v.gnss_antenna_behind_front_m;
  t.gnss_antenna_height_m = v.gnss_antenna_height_m;
  t.accelerometers = v.accelerometers;
  return t;
}

}  // namespace roadload::sim
