#pragma once
// Which model scenario a recording is compared with: the one the user names, or the built-in
// scenario whose route the drive's first GNSS fix lies on and whose set speed is nearest, or a
// cruise on the route the user gives, or, on a road no built-in scenario drives, a cruise on the
// road the drive's own GNSS traces.
#include <optional>
#include <string>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// `model` empty: a cruise on `route` (a route file) when given, else chosen as above. The model drives the truck the recording was
// made with: `vehicle` when given, else the vehicle file its meta.toml carries, else the scenario's. The run's label is the
// recording's folder name.
Parsed<RealRun> load_real_run(const std::string& recording, const std::string& model, const j1939::Database& db,
                              const std::optional<Vehicle>& vehicle = std::nullopt, const std::string& route = {});

// One line: label, model, speed, weather, mass.
std::string describe(const RealRun& run);

}  // namespace roadload::gap
