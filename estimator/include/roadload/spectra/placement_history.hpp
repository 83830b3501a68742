#pragma once
// Where the truck was, for the last few seconds: a Welch segment is taken a segment's length after
// its first instant, so the cells it belongs to are those of the past. A fixed ring of placements
// (capture time, speed, the cell under each axle); a lookup returns the latest one at or before t.
#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "roadload/time.hpp"

namespace roadload::spectra {

inline constexpr std::size_t kMaxPlacedAxles = 8;

struct Placement {
  CaptureTime t{};
  double speed_mps = 0;                     // NaN when unknown
  double s_m = 0;                           // front axle along the route; NaN when unknown
  std::array<int, kMaxPlacedAxles> cell{};  // -1: in no cell
};

class PlacementHistory {
 public:
  explicit PlacementHistory(std::size_t capacity) : ring_(capacity) {}
  void add(CaptureTime t, std::span<const int> cells, double speed_mps, double s_m) {
    Placement& p = ring_[head_];
    p.t = t;
    p.speed_mps = speed_mps;
    p.s_m = s_m;
    p.cell.fill(-1);
    for (std::size_t i = 0; i < cells.size() && i < kMaxPlacedAxles; ++i) p.cell[i] = cells[i];
    head_ = (head_ + 1) % ring_.size();
    if (size_ < ring_.size()) ++size_;
  }
  // Front-axle distance at t, linear between the placements around it; NaN before the oldest kept,
  // after the newest, or where a placement has none.
  double distance_at(CaptureTime t) const {
    for (std::size_t back = 1; back < size_; ++back) {
      const Placement& a = newest(back + 1);
      const Placement& b = newest(back);
      if (a.t > t) continue;
      if (b.t < t) return std::numeric_limits<double>::quiet_NaN();
      const double span = static_cast<double>((b.t - a.t).count());
      return span > 0 ? a.s_m + (b.s_m - a.s_m) * static_cast<double>((t - a.t).count()) / span : b.s_m;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  // The latest placement at or before t, or nullptr.
  const Placement* at(CaptureTime t) const {
    for (std::size_t back = 1; back <= size_; ++back)
      if (newest(back).t <= t) return &newest(back);
    return nullptr;
  }

  // Calls fn(from, to, placement) for each stretch of [t0, t1] under one placement, in time order.
  // Before the oldest placement kept there is none: that stretch is skipped.
  template <typename Fn>
  void for_each_stretch(CaptureTime t0, CaptureTime t1, Fn&& fn) const {
    if (size_ == 0) return;
    std::size_t back = 1;  // 1: the newest
    while (back < size_ && newest(back).t > t0) ++back;
    for (; back >= 1; --back) {
      const Placement& p = newest(back);
      const CaptureTime from = p.t > t0 ? p.t : t0;
      const CaptureTime to = back > 1 && newest(back - 1).t < t1 ? newest(back - 1).t : t1;
      if (p.t <= t1 && from < to) fn(from, to, p);
      if (back == 1) break;
    }
  }

 private:
  const Placement& newest(std::size_t back) const { return ring_[(head_ + ring_.size() - back) % ring_.size()]; }

  std::vector<Placement> ring_;
  std::size_t head_ = 0, size_ = 0;
};

}  // namespace roadload::spectra
