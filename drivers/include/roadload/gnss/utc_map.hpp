#pragma once
// UTC on the capture clock, as an offset (UTC - capture) for the daemon to show and to write into
// meta.toml (clock.utc_offset_ns). The capture clock is CLOCK_MONOTONIC and nothing here steps or
// slews it: GNSS time only refines the offset.
//
// Two kinds of evidence:
// - A fix's UTC and the capture time it was read. The read comes after the fix's epoch by the
//   receiver's output delay, the serial line, gpsd and the socket, so utc - read falls short of the
//   offset by that latency. The least-delayed of the recent fixes bounds the offset from below; how
//   much of that fix's latency is left is unknown (NMEA receivers: tens to hundreds of ms), so the
//   estimate sits in the middle of [bound, bound + max_fix_latency] with the sigma of a uniform
//   spread over it.
// - A PPS edge: the receiver's pulse at a UTC second, stamped at the edge by the kernel's PPS
//   device (or by gpsd waiting on the serial line's DCD). Good to the stamp's jitter, it governs
//   while edges keep coming. An edge that disagrees with the fixes by more than their latency
//   carries a mislabelled second and is refused.
//
// Pure computation: the source reads the clocks and passes the numbers in.
#include <array>
#include <cstddef>
#include <cstdint>

#include "roadload/time.hpp"

namespace roadload::gnss {

enum class UtcSource : std::uint8_t { none, fix_time, pps };

const char* to_string(UtcSource s);

struct UtcOffset {
  std::int64_t utc_minus_capture_ns = 0;  // UTC = capture + this
  std::int64_t sigma_ns = 0;              // one standard deviation of the offset
  UtcSource source = UtcSource::none;
};

struct UtcMapConfig {
  std::int64_t max_fix_latency_ns = 500'000'000;  // a fix is read at most this long after its epoch
  std::int64_t pps_sigma_ns = 10'000;             // edge stamp jitter: ~1 us kernel PPS, tens of us from DCD in gpsd
  std::int64_t pps_hold_ns = 2'500'000'000;       // an edge governs this long after it (two missed pulses)
  std::int64_t drift_slack_ns = 2'000'000;        // capture vs UTC drift over the fix window: 50 ppm x 16 s < 1 ms
};

struct UtcMapCounters {
  std::uint64_t fixes = 0;
  std::uint64_t edges = 0;          // PPS edges taken
  std::uint64_t edges_refused = 0;  // PPS edges off the fixes' offset by more than their latency
};

class UtcMap {
 public:
  explicit UtcMap(UtcMapConfig config = {}) : config_(config) {}

  void observe_fix(std::int64_t utc_ns, CaptureTime read);
  // The edge at which the UTC second `utc_ns` began; false when refused.
  bool observe_pps(std::int64_t utc_ns, CaptureTime edge);
  // As of the newest observation: the PPS edge's if it is recent, else the fixes'.
  UtcOffset offset() const;
  const UtcMapCounters& counters() const { return counters_; }

 private:
  static constexpr std::size_t kFixWindow = 16;
  // Lower bound of the offset from the fix window: the least-delayed fix's utc - read.
  std::int64_t fix_bound_ns() const;

  UtcMapConfig config_;
  std::array<std::int64_t, kFixWindow> fix_offsets_{};  // utc - read, ns
  std::size_t fix_head_ = 0, fix_count_ = 0;
  std::int64_t pps_offset_ns_ = 0;
  CaptureTime pps_edge_{}, newest_{};
  bool have_pps_ = false;
  UtcMapCounters counters_;
};

}  // namespace roadload::gnss
