#pragma once
// The truck as the plant's parameters, built from a vehicle description (config/vehicles/; the
// sources of its values are in its file): the quarter cars per axle, and the engine, fuel map,
// driveline and accessories as the description gives them.
#include <cstddef>
#include <string>
#include <vector>

#include "roadload/sim/vertical.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::sim {

using EngineSpec = EngineDescription;
using FuelSpec = FuelDescription;
using DrivelineSpec = DrivelineDescription;
using AccessorySpec = AccessoryDescription;

struct AxleSpec {
  std::string name;               // "front", "drive1", ...
  double position_m = 0;          // behind the front axle
  double load_kg = 0;             // static axle load
  AxleParams vertical;            // sprung share, unsprung, springs and dampers
  double tire_radius_m = 0;       // dynamic rolling radius
  double wheel_inertia_kgm2 = 0;  // all wheel ends of the axle
  bool driven = false;
};

struct TruckParams {
  std::string vin;
  std::string description;
  std::vector<AxleSpec> axles;  // front to rear, at most kMaxAxles
  EngineSpec engine;
  FuelSpec fuel;
  DrivelineSpec driveline;
  AccessorySpec accessories;
  double cda_m2 = 0;
  // This truck's tires against the pavement's own CRR (the route's cells): another brand, model
  // or wear than the tires a route's CRR was measured with.
  double tire_crr_scale = 1.0;
  double gnss_antenna_behind_front_m = 0;
  double gnss_antenna_height_m = 0;
  std::vector<AccelerometerMount> accelerometers;

  double total_mass_kg() const;
  // Distance of the centre of gravity behind the front axle, from the axle loads.
  double cg_position_m() const;
  // The first driven axle's tire radius: engine speed turns into road speed there.
  double drive_radius_m() const;
  // Index of the named axle; axles.size() when there is none.
  std::size_t axle_index(const std::string& name) const;
};

// Unsprung masses: `physical` adds the axle and part of the suspension to tires and wheels (what a
// quarter car needs); `report` uses the report's tires-and-wheels definition of Table 6.1.
enum class UnsprungDefinition { physical, report };

TruckParams truck_from_vehicle(const Vehicle& vehicle, UnsprungDefinition unsprung = UnsprungDefinition::physical);

}  // namespace roadload::sim
