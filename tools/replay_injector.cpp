#include "replay_injector.hpp"

#include <linux/can/error.h>

#include <algorithm>

#include "roadload/j1939/id.hpp"
#include "roadload/j1939/transport.hpp"

namespace roadload::cli {
namespace {

constexpr std::uint8_t kTpCmRts = 16, kTpCmBam = 32;

}  // namespace

FaultInjector::FaultInjector(const io::ReplayFaults& faults, CaptureTime first)
    : faults_(faults), first_(first), errors_(faults.error_frames), truncations_(faults.tp_truncations), random_(faults.seed) {
  std::sort(errors_.rbegin(), errors_.rend());
  std::sort(truncations_.rbegin(), truncations_.rend());
}

bool FaultInjector::due(std::vector<Nanoseconds>& at, CaptureTime t) {
  if (at.empty() || t - first_ < at.back()) return false;
  at.pop_back();
  return true;
}

void FaultInjector::error_frame(const CanFrame& like, std::uint32_t error_class, std::uint8_t byte2, std::vector<CanFrame>& out) {
  CanFrame e;
  e.t = like.t;
  e.iface = like.iface;
  e.kind = CanFrameKind::error;
  e.id = error_class;
  e.len = CAN_ERR_DLC;
  e.data[2] = byte2;
  out.push_back(e);
  ++counts_.error_frames;
}

// Remembers the first session announced after a truncation time and withholds its last packet.
bool FaultInjector::truncate_transport(const CanFrame& f) {
  if (!f.is_j1939()) return false;
  const j1939::Id id = j1939::parse_id(f.id);
  const j1939::Pgn pgn = id.pgn();
  if (pgn == j1939::kPgnTpCm && f.len >= 4 && (f.data[0] == kTpCmBam || f.data[0] == kTpCmRts) && due(truncations_, f.t)) {
    victim_ = Victim{f.iface, id.sa, f.data[3]};
  }
  if (victim_ && pgn == j1939::kPgnTpDt && f.len >= 1 && f.iface == victim_->iface && id.sa == victim_->sa &&
      f.data[0] == victim_->last_packet) {
    victim_.reset();
    ++counts_.truncated;
    return true;
  }
  return false;
}

void FaultInjector::process(const CanFrame& f, std::vector<CanFrame>& out) {
  const Nanoseconds since = f.t - first_;
  if (next_bus_off_ < faults_.bus_off.size() && since >= faults_.bus_off[next_bus_off_].at && !bus_off_) {
    error_frame(f, CAN_ERR_BUSOFF, 0, out);
    bus_off_ = true;
  }
  if (bus_off_) {
    const io::FaultWindow& w = faults_.bus_off[next_bus_off_];
    if (since < w.at + w.length) {
      ++counts_.silenced;
      return;
    }
    bus_off_ = false;
    ++next_bus_off_;
    error_frame(f, CAN_ERR_RESTARTED, 0, out);
  }
  if (due(errors_, f.t)) error_frame(f, CAN_ERR_PROT | CAN_ERR_BUSERROR, CAN_ERR_PROT_BIT, out);
  if (truncate_transport(f)) return;
  if (faults_.drop_fraction > 0 && uniform_(random_) < faults_.drop_fraction) {
    ++counts_.dropped;
    return;
  }
  out.push_back(f);
  if (faults_.duplicate_fraction > 0 && uniform_(random_) < faults_.duplicate_fraction) {
    out.push_back(f);
    ++counts_.duplicated;
  }
}

std::optional<Nanoseconds> FaultInjector::clock_step_due(CaptureTime t) {
  if (next_clock_step_ >= faults_.clock_steps.size() || t - first_ < faults_.clock_steps[next_clock_step_].at) return std::nullopt;
  return faults_.clock_steps[next_clock_step_++].by;
}

}  // namespace roadload::cli
