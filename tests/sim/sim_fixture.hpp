#pragma once
// Shared by the simulator's tests: built-in scenarios from the source tree and the in-memory drive
// of simulated_drive.hpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"
#include "simulated_drive.hpp"

namespace roadload::sim::test {

inline Scenario builtin(const std::string& name) {
  auto s = load_scenario(name, ROADLOAD_CONFIG_DIR);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
  return s.value();
}

inline j1939::Database core_database() {
  j1939::Database db;
  const auto err = load_dbc_file(db, std::string(ROADLOAD_CONFIG_DIR "/j1939-core.dbc"));
  EXPECT_FALSE(err.has_value());
  return db;
}

// The scenario driven into memory without its accelerometers: the force balance does not use them,
// and the run is three times faster.
inline MemorySink drive_without_accelerometers(Scenario sc, std::uint64_t seed, const j1939::Database& db) {
  sc.accelerometers = 0;
  Simulation sim(sc, seed, db);
  MemorySink sink;
  sim.run(sink, nullptr);
  return sink;
}

// The scenario driven into memory without its accelerometers, with the plant's truth per cell.
struct DriveWithTruth {
  MemorySink sink;
  std::vector<CellTruth> cells;
};
inline DriveWithTruth drive_with_truth(Scenario sc, std::uint64_t seed, const j1939::Database& db) {
  sc.accelerometers = 0;
  Simulation sim(sc, seed, db);
  DriveWithTruth d;
  TruthRecorder truth(sim.route(), sim.plant().truck());
  sim.run(d.sink, &truth);
  d.cells = truth.cells();
  return d;
}

}  // namespace roadload::sim::test
