#pragma once
// The CAN half of `roadload replay --faults`: what goes onto the bus for each recorded frame. The
// sensor half (GNSS outage, FIFO overflow) travels to the daemon in the replay origin.
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/io/replay_faults.hpp"

namespace roadload::cli {

struct InjectedCounts {
  std::uint64_t dropped = 0;
  std::uint64_t duplicated = 0;
  std::uint64_t error_frames = 0;  // including bus-off and restart
  std::uint64_t silenced = 0;      // frames a bus-off controller never received
  std::uint64_t truncated = 0;     // transport packets withheld
};

class FaultInjector {
 public:
  // `first`: the recording's first frame, from which fault times count.
  FaultInjector(const io::ReplayFaults& faults, CaptureTime first);

  // Appends to `out` what goes on the bus in place of the recorded frame `f`: nothing, it, it
  // twice, or error frames before it.
  void process(const CanFrame& f, std::vector<CanFrame>& out);
  // A wall-clock step due before the frame recorded at `t`, once.
  std::optional<Nanoseconds> clock_step_due(CaptureTime t);
  const InjectedCounts& counts() const { return counts_; }

 private:
  bool due(std::vector<Nanoseconds>& at, CaptureTime t);
  void error_frame(const CanFrame& like, std::uint32_t error_class, std::uint8_t byte2, std::vector<CanFrame>& out);
  bool truncate_transport(const CanFrame& f);

  const io::ReplayFaults& faults_;
  CaptureTime first_;
  std::vector<Nanoseconds> errors_, truncations_;  // still to come, latest first
  std::size_t next_bus_off_ = 0, next_clock_step_ = 0;
  bool bus_off_ = false;
  // A transport session picked for truncation: its sender and the packet to withhold.
  struct Victim {
    std::uint8_t iface, sa, last_packet;
  };
  std::optional<Victim> victim_;
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  InjectedCounts counts_;
};

}  // namespace roadload::cli
