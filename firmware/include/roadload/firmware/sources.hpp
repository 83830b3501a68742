#pragma once
// Builds the daemon's sources from its settings: a SocketCAN source per bus; accelerometers and
// GNSS from their devices, or from a recording when replaying. A source that is not configured is
// named once in `notes` and skipped; one that is configured but cannot be opened is a setup error.
#include <string>
#include <vector>

#include "roadload/firmware/config.hpp"
#include "roadload/firmware/daemon.hpp"
#include "roadload/io/replay_clock.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::firmware {

struct BuiltSources {
  DaemonSources sources;
  std::vector<std::string> interfaces;
  std::vector<CanBusInfo> buses;
  recording::Metadata replayed;  // the replayed recording's metadata, when replaying
  bool replaying = false;
  io::ReplayTiming timing;  // when replaying: recorded time -> capture time
};

Parsed<BuiltSources> build_sources(const DaemonConfig& c, io::WaitClock& clock, std::vector<std::string>& notes);

}  // namespace roadload::firmware
