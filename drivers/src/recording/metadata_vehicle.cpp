#include "roadload/recording/metadata_vehicle.hpp"

namespace roadload::recording {
namespace {

void set_if(const Metadata& meta, const std::string& key, double& value) {
  if (const auto it = meta.vehicle.find(key); it != meta.vehicle.end()) value = it->second;
}

}  // namespace

Vehicle vehicle_from_metadata(const Vehicle& base, const Metadata& meta) {
  Vehicle v = base;
  std::vector<VehicleAxle> named;
  for (VehicleAxle a : base.axles) {
    if (meta.vehicle.find(a.name + "_load_kg") == meta.vehicle.end()) continue;
    set_if(meta, a.name + "_load_kg", a.load_kg);
    set_if(meta, a.name + "_position_m", a.position_m);
    set_if(meta, a.name + "_unsprung_kg", a.unsprung_kg);
    named.push_back(std::move(a));
  }
  if (!named.empty()) v.axles = std::move(named);
  set_if(meta, "gnss_antenna_behind_front_axle_m", v.gnss_antenna_behind_front_m);
  set_if(meta, "gnss_antenna_height_m", v.gnss_antenna_height_m);
  if (const auto it = meta.vehicle_text.find("vin"); it != meta.vehicle_text.end()) v.vin = it->second;
  return v;
}

}  // namespace roadload::recording
