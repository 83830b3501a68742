#pragma once
// What a recording's meta.toml says about the truck, turned into the estimator's settings: the
// analyzer's mass, axles and antenna; the axles that carry accelerometers; the accelerometers.
// `roadload analyze` and roadloadd both start from these, so offline and live agree.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/vibration.hpp"

namespace roadload::recording {

// Mass (or `mass` when given), the axles (centre of gravity, and where each meets a new pavement)
// and the GNSS antenna; the MnROAD truck's values where the recording is silent.
AnalyzerConfig config_from_vehicle(const std::map<std::string, double>& vehicle, std::optional<double> mass);

struct LayoutResult {
  std::optional<AxleLayout> layout;  // none: no axle has its accelerometers
  std::string why_not;               // when none
  std::vector<std::string> skipped;  // axles left out, each with why
};

// The axles with accelerometers; axles without them are skipped and named. `source` names the
// metadata in messages.
LayoutResult axle_layout(const Metadata& meta, const std::string& source);

std::vector<VibrationSensor> accelerometers(const Metadata& meta);

}  // namespace roadload::recording
