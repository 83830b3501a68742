#pragma once
// How `roadload replay` tells a running roadloadd where a replay starts: a small TOML file with the
// recording's first stamp, the capture-clock time (CLOCK_MONOTONIC, the same in both processes)
// at which it was sent, the rate, and the faults injected on the way. The daemon's replay sources then hand out the recording's
// sensor streams on the same timeline as the CAN frames it hears on the interface.
#include <optional>
#include <string>

#include "roadload/io/replay_clock.hpp"
#include "roadload/io/replay_faults.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::io {

struct ReplayOrigin {
  ReplayTiming timing;
  ReplayFaults faults;  // the sensor faults apply in the daemon's replay drivers
};

// Written to a temporary name and renamed, so a reader never sees half a file.
std::optional<ParseError> write_replay_origin(const std::string& path, const ReplayOrigin& origin);
Parsed<ReplayOrigin> read_replay_origin(const std::string& path);

}  // namespace roadload::io
