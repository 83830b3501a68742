#include "roadload/spectra/segment_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadload::spectra {

SegmentWeights::SegmentWeights(const std::vector<double>& window) : cumulative_(window.size() + 1, 0.0) {
  for (std::size_t j = 0; j < window.size(); ++j) cumulative_[j + 1] = cumulative_[j] + window[j] * window[j];
}

SegmentShares SegmentWeights::shares(const PlacementHistory& h, std::size_t axle, CaptureTime t0, std::int64_t period_ns) const {
  SegmentShares out;
  const auto n = static_cast<std::int64_t>(cumulative_.size() - 1);
  const double total = cumulative_.back();
  double speed_sum = 0, speed_weight = 0;
  // Sample j lies at t0 + j * period; a stretch [from, to) holds samples ceil((from - t0) / p) ..
  const auto index = [&](CaptureTime t) {
    const std::int64_t d = (t - t0).count();
    return std::clamp<std::int64_t>(d <= 0 ? 0 : (d + period_ns - 1) / period_ns, 0, n);
  };
  const CaptureTime t1 = t0 + Nanoseconds{n * period_ns};
  h.for_each_stretch(t0, t1, [&](CaptureTime from, CaptureTime to, const Placement& p) {
    const double w = (cumulative_[static_cast<std::size_t>(index(to))] - cumulative_[static_cast<std::size_t>(index(from))]) / total;
    if (w <= 0) return;
    if (std::isfinite(p.speed_mps)) {
      speed_sum += w * p.speed_mps;
      speed_weight += w;
    }
    const int cell = axle < kMaxPlacedAxles ? p.cell[axle] : -1;
    if (cell < 0) return;
    for (std::size_t i = 0; i < out.count; ++i) {
      if (out.share[i].cell == cell) {
        out.share[i].weight += w;
        return;
      }
    }
    if (out.count < SegmentShares::kMax) out.share[out.count++] = {cell, w};
  });
  out.speed_mps = speed_weight > 0.5 ? speed_sum / speed_weight : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace roadload::spectra
