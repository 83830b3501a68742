#pragma once
// Which cells a Welch segment belongs to, and how much. A segment of one axle's signals is shared
// among the cells that axle rolled over during it, each by the share of the window's energy (sum of
// w^2) that fell in it. With the Hann window at 75 % overlap the w^2 of all segments add up to the
// same at every instant, so these weights make a cell's average the time average over the cell,
// blurred by half a segment at its ends.
#include <array>
#include <cstdint>
#include <vector>

#include "roadload/spectra/placement_history.hpp"
#include "roadload/time.hpp"

namespace roadload::spectra {

struct CellShare {
  int cell = -1;
  double weight = 0;  // share of the segment's window energy, 0..1
};

struct SegmentShares {
  static constexpr std::size_t kMax = 6;
  std::array<CellShare, kMax> share{};
  std::size_t count = 0;
  double speed_mps = 0;  // window-energy-weighted speed over the segment; NaN if unknown
};

class SegmentWeights {
 public:
  explicit SegmentWeights(const std::vector<double>& window);
  // Shares for axle `axle` of the segment whose first instant is t0, at `period_ns` per sample.
  SegmentShares shares(const PlacementHistory& h, std::size_t axle, CaptureTime t0, std::int64_t period_ns) const;

 private:
  std::vector<double> cumulative_;  // cumulative_[j] = sum of w^2 over samples 0..j-1
};

}  // namespace roadload::spectra
