#include "roadload/grade_error_scale.hpp"

#include <cmath>

#include "roadload/running_stats.hpp"

namespace roadload {
namespace {

// Each pass's departure from the passes' mean slope, per bin; NaN where fewer than two passes
// have a slope there (no mean to depart from) or this pass has none.
std::vector<std::vector<double>> residuals(const std::vector<std::vector<double>>& slopes) {
  const std::size_t bins = slopes.front().size();
  std::vector<std::vector<double>> r(slopes.size(), std::vector<double>(bins, std::nan("")));
  for (std::size_t k = 0; k < bins; ++k) {
    RunningStats s;
    for (const auto& pass : slopes) {
      if (std::isfinite(pass[k])) s.add(pass[k]);
    }
    if (s.n < 2) continue;
    for (std::size_t p = 0; p < slopes.size(); ++p) {
      if (std::isfinite(slopes[p][k])) r[p][k] = slopes[p][k] - s.mean;
    }
  }
  return r;
}

}  // namespace

double gauss_markov_mean_variance_share(double correlation_m, double length_m) {
  const double a = correlation_m / length_m;
  return 2.0 * a * (1.0 - a * (1.0 - std::exp(-1.0 / a)));
}

std::optional<double> measured_grade_error_correlation_m(const std::vector<std::vector<double>>& slopes,
                                                         const GradeErrorScaleConfig& cfg) {
  if (slopes.size() < 2 || slopes.front().empty() || !(cfg.bin_m > 0)) return std::nullopt;
  const auto block = static_cast<std::size_t>(std::lround(cfg.block_m / cfg.bin_m));
  if (block < 2) return std::nullopt;
  const std::vector<std::vector<double>> r = residuals(slopes);
  // Sliding blocks use every bin; their overlap correlates them, so the count of independent
  // ones is the whole blocks the finite runs hold.
  double point_sum = 0, block_sum = 0;
  std::size_t points = 0, blocks = 0, whole_blocks = 0;
  for (const auto& pass : r) {
    std::size_t run = 0;
    double window = 0;
    for (std::size_t k = 0; k < pass.size(); ++k) {
      if (!std::isfinite(pass[k])) {
        whole_blocks += run / block;
        run = 0;
        window = 0;
        continue;
      }
      point_sum += pass[k] * pass[k];
      ++points;
      window += pass[k];
      if (++run > block) window -= pass[k - block];
      if (run >= block) {
        block_sum += (window / static_cast<double>(block)) * (window / static_cast<double>(block));
        ++blocks;
      }
    }
    whole_blocks += run / block;
  }
  if (whole_blocks < cfg.min_blocks || blocks == 0 || point_sum <= 0) return std::nullopt;
  // Both variances carry the same (n-1)/n of removing the passes' mean: their ratio does not.
  const double share = (block_sum / static_cast<double>(blocks)) / (point_sum / static_cast<double>(points));
  const double length_m = static_cast<double>(block) * cfg.bin_m;
  // The share grows with l (to 1 as l outgrows the block): bisect within a bin and half a block.
  double lo = cfg.bin_m, hi = 0.5 * length_m;
  if (share <= gauss_markov_mean_variance_share(lo, length_m)) return lo;
  if (share >= gauss_markov_mean_variance_share(hi, length_m)) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gauss_markov_mean_variance_share(mid, length_m) < share ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace roadload
