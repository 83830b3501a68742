#pragma once
// `roadload network`: every drive in a fleet database, per section, through one model
// (estimator's network/section_network.hpp): each section's CRR with a 90 % interval, by speed
// band, the trucks' own offsets, the dynamic rolling resistance and a year's fuel for a traffic
// volume the user gives (seed report Table 6.6 for one truck, here for a road's traffic).
#include <map>
#include <string>
#include <vector>

#include "roadload/network/section_network.hpp"

namespace roadload::fleet {

struct NetworkOptions {
  double trucks_per_day = 1000;  // heavy trucks over each section per day, one direction
  double speed_band_mps = 25 / 3.6;
  double fuel_price_per_l = 0;  // 0: litres only
};

struct NetworkSection {
  std::string key, route, route_hash, cell, surface, direction;
  double start_m = 0, end_m = 0;
  bool placed = false;
  double start_lat = 0, start_lon = 0, end_lat = 0, end_lon = 0;
  int drives = 0, trucks = 0, cells = 0;  // behind the figure
  network::SectionEstimate crr;
  double speed_mps = 0;  // mean of the cells used
  double dynamic_l_per_100km = 0, dynamic_l_per_100km_se = 0;
  double rolling_l_per_pass = 0, dynamic_l_per_pass = 0;  // a truck of the fleet, once over it
  double rolling_l_per_year = 0, dynamic_l_per_year = 0;  // at the traffic volume given
};

struct NetworkBand {
  std::size_t section = 0;  // into NetworkView::sections
  double lo_mps = 0, hi_mps = 0;
  int drives = 0, trucks = 0;
  network::SectionEstimate crr;
};

struct NetworkTruck {
  std::string key, vin, name;
  int drives = 0;
  network::TruckEffect effect;
};

struct NetworkView {
  NetworkOptions options;
  std::vector<NetworkSection> sections;  // by route, then along it
  std::vector<NetworkBand> bands;
  std::vector<NetworkTruck> trucks;
  network::SectionNetworkFit fit;
  // CRR is the static one (crr_tire: the tires' on the pavement, the dynamic losses apart) when
  // every drive measured its dynamic losses; else the force balance's, dynamic losses included.
  bool static_crr = false;
  int drives = 0, cells_used = 0, cells_excluded = 0;
  std::map<std::string, int> excluded;  // why a drive's cell is not evidence, and how often
};

// Reads every section result of the database at `db_url` and fits the network. Throws
// db::DatabaseError.
NetworkView network_view(const std::string& db_url, const NetworkOptions& options);

// The outputs, as text: network.csv, network-bands.csv, trucks.csv, network.geojson, network.json
// and the self-contained map page network.html.
std::map<std::string, std::string> network_files(const NetworkView& view);

}  // namespace roadload::fleet
