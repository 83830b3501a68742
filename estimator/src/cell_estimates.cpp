#include "roadload/cell_estimates.hpp"

#include <algorithm>
#include <string>

namespace roadload {

CellResult cell_result(const CellSpan& span, const CellTally& tally, std::optional<CrrMean> crr, const CellLimits& limits) {
  CellResult r;
  r.id = span.id;
  r.start_m = span.start_m;
  r.end_m = span.end_m;
  r.samples = tally.samples;
  if (tally.samples == 0 || !crr) {
    // Name the commonest reason, so a missing input shows as itself and not as a blank.
    const auto& why = tally.why;
    const auto worst = static_cast<std::size_t>(std::max_element(why.begin() + 1, why.end()) - why.begin());
    r.reason = tally.seen == 0 ? std::string("not driven")
                               : std::string("no usable force balance: ") + to_string(static_cast<Unusable>(worst)) + " (" +
                                     std::to_string(why[worst]) + " of " + std::to_string(tally.seen) + " ticks)";
    return r;
  }
  r.crr = crr->crr;
  r.crr_sigma = crr->sigma;
  r.crr_lo = r.crr - limits.interval_z * r.crr_sigma;
  r.crr_hi = r.crr + limits.interval_z * r.crr_sigma;
  r.speed_mps = tally.speed_sum_mps / static_cast<double>(tally.samples);
  r.weight_n = limits.weight_n;
  r.roll_force_n = r.crr * limits.weight_n;
  judge_cell(r, limits.identified_sigma, limits.identification, limits.drive_failures);
  return r;
}

CellEstimates::CellEstimates(std::vector<CellSpan> cells, double truck_length_m, bool smoothed)
    : cells_(std::move(cells)), state_(cells_.size()), truck_length_m_(truck_length_m), smoothed_(smoothed) {}

void CellEstimates::add(CellTally& sum, const CellTally& t) {
  sum.seen += t.seen;
  sum.samples += t.samples;
  sum.speed_sum_mps += t.speed_sum_mps;
  for (std::size_t k = 0; k < t.why.size(); ++k) sum.why[k] += t.why[k];
}

bool CellEstimates::inside(const CellSpan& c, double s_front_m, double s_cg_m) const {
  return c.end_m - c.start_m > truck_length_m_ ? s_front_m - truck_length_m_ >= c.start_m && s_front_m < c.end_m
                                               : s_cg_m >= c.start_m && s_cg_m < c.end_m;
}

void CellEstimates::tick(double s_front_m, double s_cg_m, double speed_mps, Unusable why, CrrMean filter_now, std::size_t step) {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (!inside(cells_[i], s_front_m, s_cg_m)) continue;
    Cell& c = state_[i];
    ++c.tally.seen;
    ++c.tally.why[static_cast<std::size_t>(why)];
    if (why != Unusable::none) continue;
    ++c.tally.samples;
    c.tally.speed_sum_mps += speed_mps;
    if (smoothed_) {
      c.steps.push_back(step);
    } else {
      c.live = filter_now;
    }
  }
}

std::vector<std::size_t> CellEstimates::group_steps(const PavementGroups& groups, std::size_t group) const {
  std::vector<std::size_t> steps;
  for (std::size_t i = 0; i < cells_.size() && i < groups.cell_group.size(); ++i) {
    if (groups.cell_group[i] == static_cast<int>(group)) steps.insert(steps.end(), state_[i].steps.begin(), state_[i].steps.end());
  }
  return steps;
}

int CellEstimates::cell_at(double s_m) const {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (s_m >= cells_[i].start_m && s_m < cells_[i].end_m) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace roadload
