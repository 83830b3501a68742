#include "roadload/j1939/cadence.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "roadload/j1939/id.hpp"
#include "roadload/j1939/transport.hpp"

namespace roadload::j1939 {
namespace {

constexpr Pgn kPgnRequest = 0xEA00;
constexpr double kGapPeriods = 1.6;
constexpr double kRepeatPeriods = 0.2;
constexpr double kOnTimePeriods = 0.75;  // from here to kGapPeriods an interval is ordinary
constexpr double kWholePeriods = 0.3;    // how near a whole number of periods a loss's interval is
// The period follows slow drift of the sender's clock, not single late frames.
constexpr double kPeriodGain = 0.05;

constexpr Nanoseconds kWindow{1'000'000};
constexpr Nanoseconds kPause{1'000'000'000};

// The first `len` (at most 8) of 8 readable bytes as one number: two frames' data compare in one
// load each, where a memcmp call per frame showed in a decode's profile.
std::uint64_t first_bytes(const std::uint8_t* data, std::uint8_t len) {
  std::uint64_t v;
  std::memcpy(&v, data, sizeof v);
  if (len >= 8) return v;
  if constexpr (std::endian::native == std::endian::little) return v & ((std::uint64_t{1} << (8 * len)) - 1);
  return len == 0 ? 0 : v >> (8 * (8 - len));
}

bool bursty(Pgn pgn) { return pgn == kPgnTpCm || pgn == kPgnTpDt || pgn == kPgnEtpCm || pgn == kPgnEtpDt || pgn == kPgnRequest; }

}  // namespace

CadenceMonitor::Slot* CadenceMonitor::slot(std::uint8_t iface, std::uint32_t key) {
  // Fibonacci hashing takes the product's top bits: its low bits depend only on the key's low
  // bits, the source address, which a truck's few ECUs share across dozens of messages.
  static_assert(std::has_single_bit(kSlots));
  constexpr int kSlotBits = std::countr_zero(kSlots);
  const std::uint32_t h = (key ^ (std::uint32_t{iface} << 29)) * 2654435761u;
  const std::size_t start = h >> (32 - kSlotBits);
  for (std::size_t i = 0; i < kSlots; ++i) {
    Slot& s = slots_[(start + i) & (kSlots - 1)];
    if (!s.used) {
      s.used = true;
      s.iface = iface;
      s.key = key;
      return &s;
    }
    if (s.key == key && s.iface == iface) return &s;
  }
  return nullptr;
}

void CadenceMonitor::learn(Slot& s, double dt_s) {
  s.learning[s.learned++] = dt_s;
  if (s.learned < kLearnIntervals) return;
  std::nth_element(s.learning.begin(), s.learning.begin() + kLearnIntervals / 2, s.learning.end());
  s.period_s = s.learning[kLearnIntervals / 2];
  s.learned = 0;
  s.off_period = 0;
}

// A loss shows as an interval of a whole number of periods between two ordinary ones; a repeat
// as the same frame again at once between two ordinary intervals. A late frame followed by a burst
// (a stalled sender catching up) matches neither.
void CadenceMonitor::judge(Slot& s, double dt_s, bool same) {
  const double r = dt_s / s.period_s;
  const auto ordinary = [](double periods) { return periods >= kOnTimePeriods && periods < kGapPeriods; };
  if (ordinary(r)) {
    if (s.pending == Pending::gap) ++counters_.gaps;
    if (s.pending == Pending::repeat) ++counters_.repeats;
  }
  s.pending = Pending::none;
  // The previous interval is looked at only for a frame that may be a repeat or follow a loss,
  // so an ordinary frame costs one division, not two.
  const bool maybe_repeat = same && r < kRepeatPeriods;
  const bool maybe_gap = r >= kGapPeriods && std::abs(r - std::round(r)) < kWholePeriods;
  if ((maybe_repeat || maybe_gap) && ordinary(s.last_dt_s / s.period_s)) s.pending = maybe_repeat ? Pending::repeat : Pending::gap;
  if (ordinary(r)) {
    s.period_s += kPeriodGain * (dt_s - s.period_s);
    s.off_period = 0;
    return;
  }
  const int direction = r >= kGapPeriods ? 1 : -1;
  s.off_period = direction == s.off_direction ? s.off_period + 1 : 1;
  s.off_direction = direction;
  if (s.off_period >= kRelearnIntervals) {
    s.period_s = 0;
    s.pending = Pending::none;
    s.off_period = 0;
  }
}

void CadenceMonitor::push(const CanFrame& frame) {
  if (frame.t - window_start_ >= kWindow || frame.t < window_start_) {
    window_start_ = frame.t;
    window_frames_ = 0;
  }
  if (++window_frames_ > kMaxFramesPerWindow) paused_until_ = frame.t + kPause;
  if (!frame.is_j1939() || bursty(pgn_of(frame.id))) return;
  Slot* s = slot(frame.iface, frame.id & 0x03FFFFFFu);
  if (s == nullptr) {
    ++counters_.untracked;
    return;
  }
  const std::uint8_t len = std::min<std::uint8_t>(frame.len, 8);
  const bool same = s->len == len && first_bytes(frame.data.data(), len) == first_bytes(s->data.data(), len);
  const bool first = !s->seen;
  const double dt_s = to_seconds(frame.t - s->last);
  s->seen = true;
  s->last = frame.t;
  s->len = len;
  // All eight bytes in one move: `len` says how many of them count.
  std::memcpy(s->data.data(), frame.data.data(), s->data.size());
  if (frame.t < paused_until_) {
    ++counters_.too_fast;
    s->pending = Pending::none;
    s->last_dt_s = 0;
    return;
  }
  if (first || dt_s < 0) return;
  if (s->period_s > 0) {
    judge(*s, dt_s, same);
  } else {
    learn(*s, dt_s);
  }
  s->last_dt_s = dt_s;
}

}  // namespace roadload::j1939
