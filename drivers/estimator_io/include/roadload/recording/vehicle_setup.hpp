#pragma once
// A recording's truck turned into the estimator's settings: the analyzer's truck, mass, axles and
// antenna; the axles that carry accelerometers; the accelerometers. `roadload analyze` and
// roadloadd both start from these, so offline and live agree.
#include <optional>
#include <string>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/vehicle.hpp"
#include "roadload/vibration.hpp"

namespace roadload::recording {

// `vehicle` (the recording's: recording/metadata_vehicle.hpp) as the analyzer takes it, with the
// mass declared in meta.toml (vehicle.mass_kg), or `mass` when given, over the axles' sum.
AnalyzerConfig analyzer_config_for(const Vehicle& vehicle, const Metadata& meta, std::optional<double> mass);

struct LayoutResult {
  std::optional<AxleLayout> layout;  // none: no axle has its accelerometers
  std::string why_not;               // when none
  std::vector<std::string> skipped;  // axles left out, each with why
};

// The vehicle's axles with accelerometers among the recording's sensors; axles without them are
// skipped and named. `source` names the metadata in messages.
LayoutResult axle_layout(const Metadata& meta, const Vehicle& vehicle, const std::string& source);

std::vector<VibrationSensor> accelerometers(const Metadata& meta);

}  // namespace roadload::recording
