#pragma once
// Where a drive's fuel went, over the trip and in each cell (fuel_breakdown.hpp): the power of
// every interval between filter ticks is kept, and once the smoother has run each interval's
// resistances come from the smoothed CRR and CdA at its end.
#include <cstddef>
#include <deque>
#include <vector>

#include "roadload/crr_filter.hpp"
#include "roadload/fuel_breakdown.hpp"

namespace roadload {

class DriveFuel {
 public:
  struct Interval {
    PowerInterval power;   // its resistances are filled in by finish()
    std::size_t step = 0;  // the smoother step of the estimate at its end
    int cell = -1;         // under the centre of gravity at its end; -1 off the cells
    double air_density_kgpm3 = 0, headwind_mps = 0, grade_rad = 0;
  };

  void add(const Interval& i) { intervals_.push_back(i); }
  // `state(step)` is the smoothed state at a step.
  template <typename State>
  void finish(double mass_kg, std::size_t cell_count, State&& state) {
    cells_.assign(cell_count, FuelBreakdown{});
    for (Interval& i : intervals_) {
      fill_resistances(i, mass_kg, state(i.step));
      trip_.add(i.power);
      if (i.cell >= 0) cells_[static_cast<std::size_t>(i.cell)].add(i.power);
    }
  }
  const FuelBreakdown& trip() const { return trip_; }
  // Empty before finish().
  const std::vector<FuelBreakdown>& cells() const { return cells_; }

 private:
  static void fill_resistances(Interval& i, double mass_kg, const CrrFilter::Vec& x);

  std::deque<Interval> intervals_;  // a drive's worth: grown in blocks, never copied as a vector would be
  FuelBreakdown trip_;
  std::vector<FuelBreakdown> cells_;
};

}  // namespace roadload
