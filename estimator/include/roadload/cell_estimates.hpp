#pragma once
// Each cell's CRR from the ticks of the drive that fall in it, live or smoothed behind one
// interface. Live (roadloadd), a cell keeps the filter's estimate at its last usable tick: all the
// cell taught the filter, without the data after it, in memory fixed at construction. Smoothed
// (offline), a cell's CRR is the mean of the smoothed CRR over its usable ticks. Either way a
// cell's interval, identification and reason come from cell_result().
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "roadload/cell_span.hpp"
#include "roadload/drive_results.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/identification.hpp"
#include "roadload/pavement_groups.hpp"

namespace roadload {

// A CRR estimate and its standard error.
struct CrrMean {
  double crr = 0, sigma = 0;
};

// What a cell saw of the drive.
struct CellTally {
  std::size_t seen = 0;     // ticks with the truck on it
  std::size_t samples = 0;  // of them usable
  std::array<std::size_t, kUnusableCount> why{};
  double speed_sum_mps = 0;  // over the usable ticks
};

struct CellLimits {
  double weight_n = 0;          // the truck's weight that CRR is a coefficient of
  double interval_z = 0;        // of the two-sided interval
  double identified_sigma = 0;  // a larger sigma is not identified
  IdentificationLimits identification;
  // The drive's own failed checks (drive_failures()): a cell of a drive the model does not fit is
  // not identified either.
  std::vector<std::string> drive_failures;
};

// The one place a cell's interval, identification and reason are set.
CellResult cell_result(const CellSpan& span, const CellTally& tally, std::optional<CrrMean> crr, const CellLimits& limits);

class CellEstimates {
 public:
  // A cell longer than `truck_length_m` is read while the whole truck is on it; a shorter one while
  // its centre of gravity is. `smoothed`: keep each usable tick's smoother step.
  CellEstimates(std::vector<CellSpan> cells, double truck_length_m, bool smoothed);

  // A filter tick: each cell the truck is on counts it. A usable one updates the cell's live
  // estimate to the filter's now, or keeps its smoother step.
  void tick(double s_front_m, double s_cg_m, double speed_mps, Unusable why, CrrMean filter_now, std::size_t step);

  // The cells' results; smoothed, each CRR is `mean(i, steps)` of cell i's usable ticks' steps (a
  // CrrMean, or an optional one: none leaves the cell without a CRR).
  template <typename Mean>
  std::vector<CellResult> results(const CellLimits& limits, Mean&& mean) const {
    std::vector<CellResult> out;
    for (std::size_t i = 0; i < cells_.size(); ++i) {
      const Cell& c = state_[i];
      std::optional<CrrMean> crr;
      if (c.tally.samples > 0) crr = smoothed_ ? std::optional<CrrMean>(mean(i, steps(i))) : c.live;
      out.push_back(cell_result(cells_[i], c.tally, crr, limits));
    }
    return out;
  }

  // Each pavement group's result over all its cells' usable ticks together (`groups.cell_group`
  // gives each cell's group), its CRR `mean(g, steps)`. Smoothed only: a live filter's estimate
  // belongs to a place, not to a pavement spread along the route, so live every group says so.
  template <typename Mean>
  std::vector<CellResult> group_results(const PavementGroups& groups, const CellLimits& limits, Mean&& mean) const {
    std::vector<CellResult> out;
    for (std::size_t g = 0; g < groups.names.size(); ++g) {
      CellSpan span{groups.names[g], 0, 0};
      CellTally tally;
      for (std::size_t i = 0; i < cells_.size() && i < groups.cell_group.size(); ++i) {
        if (groups.cell_group[i] != static_cast<int>(g)) continue;
        span.end_m += cells_[i].end_m - cells_[i].start_m;
        add(tally, state_[i].tally);
      }
      const std::vector<std::size_t> steps = group_steps(groups, g);
      std::optional<CrrMean> crr;
      if (smoothed_ && !steps.empty()) crr = mean(g, std::span<const std::size_t>(steps));
      out.push_back(cell_result(span, tally, crr, limits));
      if (!smoothed_ && tally.samples > 0) out.back().reason = "per pavement only from the smoothed drive (roadload analyze)";
    }
    return out;
  }

  const std::vector<CellSpan>& spans() const { return cells_; }
  // The smoother steps of a cell's usable ticks (smoothed only), and of a pavement group's cells'.
  std::span<const std::size_t> steps(std::size_t cell) const { return state_[cell].steps; }
  std::vector<std::size_t> group_steps(const PavementGroups& groups, std::size_t group) const;
  // The cell at a place along the route; -1 off the cells.
  int cell_at(double s_m) const;

 private:
  bool inside(const CellSpan& c, double s_front_m, double s_cg_m) const;
  static void add(CellTally& sum, const CellTally& t);

  struct Cell {
    CellTally tally;
    CrrMean live;
    std::vector<std::size_t> steps;
  };
  std::vector<CellSpan> cells_;
  std::vector<Cell> state_;
  double truck_length_m_;
  bool smoothed_;
};

}  // namespace roadload
