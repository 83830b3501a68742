#pragma once
// A recording's GNSS track for the commands that trace or survey a road (grade, route build,
// analyze without a route): gnss.csv's fixes, else the position the truck's own bus broadcasts
// (VP1, with VDS's altitude where sent), and the antenna height that turns them into road heights.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/j1939/database.hpp"
#include "roadload/samples.hpp"

namespace roadload::cli {

struct RecordedTrack {
  std::string path;
  std::vector<GnssFix> fixes;
  double antenna_height_m = 0;
  std::string source;  // "gnss.csv", "J1939 VP1" or "J1939 VP1 and VDS"
};

struct TrackOptions {
  std::string vehicle;                     // --vehicle, whose antenna height the recordings share
  std::optional<double> antenna_height_m;  // --antenna-height, over any vehicle's
  bool print_errors = true;                // false where the command reads the recording again anyway
};

// Reads one recording (`segments`: one path, or one drive's segments in order); malformed lines
// are printed and counted in `malformed`. On an error that stops the command it is printed and the
// exit code returned.
std::optional<int> read_recorded_track(std::string_view command, const std::vector<std::string>& segments, const TrackOptions& o,
                                       const j1939::Database& db, RecordedTrack& t, std::uint64_t& malformed);

}  // namespace roadload::cli
