#pragma once
// Which model scenario a recording is compared with: the one the user names, or the built-in
// scenario whose route the drive's first GNSS fix lies on and whose set speed is nearest.
#include <string>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// `model` empty: chosen as above. The run's label is the recording's folder name.
Parsed<RealRun> load_real_run(const std::string& recording, const std::string& model, const j1939::Database& db);

// One line: label, model, speed, weather, mass.
std::string describe(const RealRun& run);

}  // namespace roadload::gap
