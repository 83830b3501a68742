#pragma once
// What a logger can tell of frames lost or repeated before they reached it: most J1939 messages
// are sent at a fixed rate, so each (bus, PGN, source address) has a period. An interval of two or
// more whole periods means frames went missing on the way (a gap); the same frame again within a
// fifth of a period is a repeat. Each is judged only between ordinary intervals: a sender that
// stalls and then catches up delivers a late frame followed by a burst, which is late delivery,
// not loss. Transport packets and requests, which come in bursts, are not
// tracked. Fixed table, no allocation: it runs in the daemon's data path.
#include <array>
#include <cstdint>

#include "roadload/can_frame.hpp"

namespace roadload::j1939 {

struct CadenceCounters {
  std::uint64_t gaps = 0;
  std::uint64_t repeats = 0;
  std::uint64_t untracked = 0;  // frames of messages beyond the table's size
  std::uint64_t too_fast = 0;   // frames not judged: arriving faster than any CAN bus carries them
};

class CadenceMonitor {
 public:
  static constexpr std::size_t kSlots = 128;
  // Intervals whose median becomes a message's period.
  static constexpr std::size_t kLearnIntervals = 8;
  // Intervals in a row all longer or all shorter than the period: the sender changed its rate,
  // and the period is learned again.
  static constexpr std::size_t kRelearnIntervals = 32;
  // More frames than this in 1 ms is beyond a 1 Mbit/s bus (7.8 29-bit frames per ms): a replay
  // at full speed, whose stamps say when frames were read, not sent. Judging pauses for a second.
  static constexpr std::uint32_t kMaxFramesPerWindow = 10;

  void push(const CanFrame& frame);
  const CadenceCounters& counters() const { return counters_; }

 private:
  enum class Pending : std::uint8_t { none, gap, repeat };
  struct Slot {
    bool used = false;
    bool seen = false;  // `last` holds a frame's stamp
    std::uint8_t iface = 0;
    std::uint32_t key = 0;  // the id without its priority bits
    CaptureTime last{};
    double period_s = 0;  // 0 while learning
    double last_dt_s = 0;
    std::array<double, kLearnIntervals> learning{};
    std::size_t learned = 0;     // intervals in `learning`
    std::size_t off_period = 0;  // off-period intervals in a row, in one direction
    int off_direction = 0;       // +1 longer, -1 shorter
    Pending pending = Pending::none;
    std::uint8_t len = 0;
    std::array<std::uint8_t, 8> data{};
  };
  Slot* slot(std::uint8_t iface, std::uint32_t key);
  void judge(Slot& s, double dt_s, bool same);
  void learn(Slot& s, double dt_s);

  std::array<Slot, kSlots> slots_{};
  CadenceCounters counters_;
  CaptureTime window_start_{};
  std::uint32_t window_frames_ = 0;
  CaptureTime paused_until_{};
};

}  // namespace roadload::j1939
