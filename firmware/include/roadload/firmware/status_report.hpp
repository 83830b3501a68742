#pragma once
// What roadloadd tells a person with `tail -f status.log` and a program reading status.jsonl, one
// line per interval: the estimate, each source's rate, drops and state, the recording, clock sync
// and the warnings that need someone's attention.
#include <cstdint>
#include <string>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/firmware/recorder.hpp"
#include "roadload/io/source.hpp"
#include "roadload/j1939/cadence.hpp"
#include "roadload/j1939/transport.hpp"

namespace roadload::firmware {

enum class SourceKind : std::uint8_t { can, accelerometer, gnss, weather };
const char* to_string(SourceKind k);

struct SourceReport {
  std::string name;
  SourceKind kind = SourceKind::can;
  io::SourceStatus status;
  double rate_per_s = 0;              // items over the last interval
  double bus_load = 0;                // CAN: fraction of the bit rate, unstuffed bits as canbusload counts them
  std::uint64_t ring_dropped = 0;     // lost because a consumer fell behind
  std::uint64_t dropped_recent = 0;   // source + ring drops in the last interval
  std::uint64_t errors_recent = 0;    // device or bus errors in the last interval
  std::uint64_t restarts_recent = 0;  // recoveries in the last interval (a bus-off shorter than it)
};

// What the decoded J1939 traffic says about frames lost or mangled before the gateway.
struct J1939Report {
  j1939::CadenceCounters cadence;
  std::uint64_t tp_completed = 0;
  std::uint64_t tp_incomplete = 0;  // timed out, superseded by a new announcement, or aborted
  // Transport frames no sender would send: data packets with no session open, sessions announced
  // and never finished, packets out of sequence, control frames malformed, announcements with no
  // session left to take them. A few a day are a noisy bus; dozens a second are a flood.
  std::uint64_t tp_anomalies = 0;
  // In the last interval.
  std::uint64_t gaps_recent = 0, repeats_recent = 0, tp_incomplete_recent = 0, tp_anomalies_recent = 0;
  double tp_anomaly_rate = 0;  // per second over the last interval
};

// The rate of transport anomalies above which the status warns of a flood: a sound bus shows none.
inline constexpr double kTpFloodPerSecond = 20.0;

struct SyncReport {
  std::uint64_t clock_steps = 0;      // wall-clock steps seen under the CAN stamps
  std::uint64_t unplaced_stamps = 0;  // CAN stamps stamped at read instead
  bool utc_known = false;
};

struct StatusReport {
  std::int64_t utc_ns = 0;  // wall clock when written, for people; the data use the capture clock
  double uptime_s = 0;
  LiveEstimate estimate;
  std::string cell;             // name of estimate.cell, empty off the cells
  double dynamic_power_w = -1;  // suspension + tires, last window; negative when not available
  std::vector<SourceReport> sources;
  RecorderStatus recording;
  bool recording_enabled = true;
  SyncReport sync;
  J1939Report j1939;
  std::vector<std::string> warnings;
};

// The warnings a report implies (sources down, drops, recording errors), in order of urgency.
std::vector<std::string> warnings_for(const StatusReport& r);
std::string format_text(const StatusReport& r);
std::string format_json(const StatusReport& r);

}  // namespace roadload::firmware
