#pragma once
// What analyze's results came from (results/provenance.hpp): the recording, the truck as
// described or assumed, the road it was placed on, the force balance's calibration.
#include <string>
#include <vector>

#include "analyze_options.hpp"
#include "gnss_tracks.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/results/provenance.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::cli {

using results::Provenance;

// A road as results name it: equal hashes, the same geometry cut into the same sections.
struct RouteIdentity {
  std::string name, hash;
};

// What trip.json says the results of `o` came from: the truck as described (or why assumed), the
// road the drive was placed on and the configuration the force balance ran with.
Provenance provenance(const AnalyzeOptions& o, const recording::Metadata& meta, const Vehicle& vehicle, const std::string& assumed,
                      const RecordedTrack& track, const AnalyzerConfig& cfg, const RouteIdentity& road);

}  // namespace roadload::cli
