#include "roadload/gnss/utc_map.hpp"

#include <algorithm>
#include <cmath>

namespace roadload::gnss {

const char* to_string(UtcSource s) {
  switch (s) {
    case UtcSource::none: return "none";
    case UtcSource::fix_time: return "fix time";
    case UtcSource::pps: return "pps";
  }
  return "?";
}

void UtcMap::observe_fix(std::int64_t utc_ns, CaptureTime read) {
  ++counters_.fixes;
  fix_offsets_[fix_head_] = utc_ns - to_ns(read);
  fix_head_ = (fix_head_ + 1) % kFixWindow;
  fix_count_ = std::min(fix_count_ + 1, kFixWindow);
  newest_ = std::max(newest_, read);
}

bool UtcMap::observe_pps(std::int64_t utc_ns, CaptureTime edge) {
  const std::int64_t offset = utc_ns - to_ns(edge);
  if (fix_count_ > 0) {
    const std::int64_t bound = fix_bound_ns();
    if (offset < bound - config_.drift_slack_ns || offset > bound + config_.max_fix_latency_ns + config_.drift_slack_ns) {
      ++counters_.edges_refused;
      return false;
    }
  }
  ++counters_.edges;
  pps_offset_ns_ = offset;
  pps_edge_ = edge;
  have_pps_ = true;
  newest_ = std::max(newest_, edge);
  return true;
}

UtcOffset UtcMap::offset() const {
  if (have_pps_ && (newest_ - pps_edge_).count() <= config_.pps_hold_ns)
    return {pps_offset_ns_, config_.pps_sigma_ns, UtcSource::pps};
  if (fix_count_ == 0) return {};
  const std::int64_t width = config_.max_fix_latency_ns;
  return {fix_bound_ns() + width / 2, std::llround(static_cast<double>(width) / std::sqrt(12.0)), UtcSource::fix_time};
}

std::int64_t UtcMap::fix_bound_ns() const {
  return *std::max_element(fix_offsets_.begin(), fix_offsets_.begin() + static_cast<std::ptrdiff_t>(fix_count_));
}

}  // namespace roadload::gnss
