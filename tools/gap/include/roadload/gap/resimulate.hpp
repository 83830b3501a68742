#pragma once
// Step 1 of the diagnosis: drive the simulator with what a recording says happened (its route from
// the model scenario; its speed, weather and vehicle mass from the recording) and reduce both the
// recording and the simulation to the same features.
#include <cstdint>
#include <string>

#include "roadload/gap/features.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/sim/scenario.hpp"

namespace roadload::gap {

// Road bins from the route's cells (250 m bins where a route has none).
RunLayout layout_for(const sim::RouteDef& route);

struct RecordedRun {
  recording::Metadata meta;
  RunFeatures features;
  recording::ErrorLog malformed;  // lines skipped as the format says, each to be told
};

// Reads a recording folder. Malformed lines are skipped and kept in `malformed`, as every command
// skips them; beyond 1 % of the records read the recording is refused: a diagnosis of damaged data
// would blame the model for the damage.
// `base` is the vehicle the recording's metadata is read over (the model's).
Parsed<RecordedRun> read_run(const std::string& path, const j1939::Database& db, const RunLayout& layout, const Vehicle& base);

// The model scenario, told the recording's mean speed, weather, duration, and the mass and the
// driving before it in its metadata. Effects stay as the model has them.
sim::Scenario resimulation(const sim::Scenario& model, const RunConditions& c, const recording::Metadata& meta);
// How long the truck had been driving when the recording starts (its tires' warm-up): meta.toml's
// driven_before_s, else the model's (by default the report's 30 minutes; roadloadd does not write it).
Seconds driven_before(const recording::Metadata& meta, const sim::Scenario& model);

// Simulates in memory, straight into features; the metadata is what its recording would hold.
RecordedRun simulate_run(const sim::Scenario& scenario, std::uint64_t seed, const j1939::Database& db, const RunLayout& layout);

}  // namespace roadload::gap
