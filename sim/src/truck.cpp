#include "roadload/sim/truck.hpp"

namespace roadload::sim {

double TruckParams::total_mass_kg() const {
  double m = 0;
  for (const auto& a : axles) m += a.load_kg;
  return m;
}

double TruckParams::cg_position_m() const {
  double moment = 0;
  for (const auto& a : axles) moment += a.load_kg * a.position_m;
  return moment / total_mass_kg();
}

namespace {

AxleSpec axle(const char* name, double position_m, double load_kg, double unsprung_kg, double k_susp, double k_tire,
              double tires, double radius_m, bool driven) {
  AxleSpec a;
  a.name = name;
  a.position_m = position_m;
  a.load_kg = load_kg;
  a.vertical.sprung_kg = load_kg - unsprung_kg;
  a.vertical.unsprung_kg = unsprung_kg;
  a.vertical.k_susp_npm = k_susp;
  a.vertical.c_susp_nspm = 20000.0;      // S Ch. 6: per axle
  a.vertical.k_tire_npm = k_tire;
  a.vertical.c_tire_nspm = 4000.0 * tires;  // S Ch. 6: per tire
  a.tire_radius_m = radius_m;
  a.wheel_inertia_kgm2 = 13.0 * tires;   // tire, wheel, drum and hub per position
  a.driven = driven;
  return a;
}

}  // namespace

TruckParams mnroad_truck(UnsprungDefinition unsprung) {
  const bool report = unsprung == UnsprungDefinition::report;
  // Report definition: tires and wheels scaled to Table 6.1's 1,463 kg (Table 6.2's parts give 1,458).
  const double front_u = report ? 178.6 : 421.0;
  const double drive_u = report ? 321.1 : 701.5;
  const double trailer_u = report ? 321.1 : 595.0;
  TruckParams t;
  t.axles = {
      axle("front", 0.0, 5307.0, front_u, 700e3, 1.9e6, 2, 0.530, false),
      axle("drive1", 5.14, 7734.0, drive_u, 800e3, 3.4e6, 4, 0.500, true),
      axle("drive2", 6.46, 7734.0, drive_u, 800e3, 3.4e6, 4, 0.500, true),
      axle("trailer1", 16.45, 7688.5, trailer_u, 800e3, 3.4e6, 4, 0.500, false),
      axle("trailer2", 17.69, 7688.5, trailer_u, 800e3, 3.4e6, 4, 0.500, false),
  };
  return t;
}

}  // namespace roadload::sim
