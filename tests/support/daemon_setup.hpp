#pragma once
// The daemon wired for a simulated scenario, as roadloadd wires itself for a truck: recording into
// a folder and, with `estimate`, the live CRR filter and spectra on the scenario's route.
#include <string>

#include "roadload/firmware/daemon.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/recording/vehicle_setup.hpp"
#include "simulated_drive.hpp"

namespace roadload::firmware::test {

inline DaemonSetup simulated_daemon_setup(const sim::Scenario& sc, const recording::Metadata& meta, const j1939::Database& db,
                                          const std::string& data_dir, bool estimate) {
  DaemonSetup setup;
  RecorderConfig rc;
  rc.data_dir = data_dir;
  setup.recording = rc;
  setup.metadata = meta;
  setup.interfaces = {"can0"};
  setup.buses = {CanBusInfo{}};
  if (!estimate) return setup;
  setup.db = &db;
  setup.route = *RouteGeometry::build(sc.route.points);
  setup.cells = sim::test::cell_spans(sc);
  const Vehicle vehicle = recording::vehicle_from_metadata(sc.vehicle, meta);
  setup.analyzer = recording::analyzer_config_for(vehicle, meta, std::nullopt);
  setup.layout = recording::axle_layout(meta, vehicle, "simulation").layout;
  setup.accelerometers = recording::accelerometers(meta);
  const PavementGroups groups = sim::test::pavement_groups(sc);
  setup.cell_group = groups.cell_group;
  setup.group_count = groups.names.size();
  return setup;
}

}  // namespace roadload::firmware::test
