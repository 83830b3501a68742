#pragma once
// Faults a bench replay injects on the way to roadloadd, so that its handling of a bad bus, a lost
// fix or an overflowing FIFO can be tested on vcan: `roadload replay --faults SPEC`.
//
// SPEC is a comma-separated list; times are seconds of the recording since its first CAN frame:
//   drop=P             each CAN frame is lost with probability P
//   dup=P              each CAN frame is sent twice with probability P
//   seed=N             the random choices' seed (default 1), so a run can be repeated
//   error@T            a CAN error frame (protocol violation) at T
//   busoff@T+D         the controller goes bus-off at T: an error frame, D seconds of silence, then
//                      an error frame saying it restarted
//   tp-truncate@T      the first transport session announced at or after T loses its last packet
//   gnss-outage@T+D    no GNSS fix from T for D seconds (the daemon's replay driver withholds them)
//   accel-overflow@T   the accelerometer FIFO overflows at T: a FIFO's worth of samples is lost and
//                      reported by the driver
//   clock-step@T=S     the wall clock (CLOCK_REALTIME) is stepped by S seconds at T; needs root
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/time.hpp"

namespace roadload::io {

struct FaultWindow {
  Nanoseconds at{};      // since the recording's first CAN frame
  Nanoseconds length{};  // zero for an instant
};

struct ClockStep {
  Nanoseconds at{};
  Nanoseconds by{};
};

struct ReplayFaults {
  double drop_fraction = 0;
  double duplicate_fraction = 0;
  std::uint64_t seed = 1;
  std::vector<Nanoseconds> error_frames;
  std::vector<FaultWindow> bus_off;
  std::vector<Nanoseconds> tp_truncations;
  std::vector<FaultWindow> gnss_outages;
  std::vector<Nanoseconds> accel_overflows;
  std::vector<ClockStep> clock_steps;
  std::string spec;  // as given: written into the replay origin for the daemon's replay drivers

  bool empty() const { return spec.empty(); }
};

// An error names the item and says what was expected (source "--faults", line 0).
Parsed<ReplayFaults> parse_replay_faults(std::string_view spec);

// The samples an accelerometer FIFO overflow loses: the ADXL355's FIFO holds 32 three-axis samples.
inline constexpr std::size_t kAccelFifoSamples = 32;

}  // namespace roadload::io
