#pragma once
// The force balance's CRR is everything that resists rolling: the tires' own hysteresis, and the
// road's roughness, whose bounce the suspensions and tires dissipate (seed report Eq. 2.7-2.8; 0.2 kW
// on the Mainline at 30 mph, 1.5 kW on TH 10 at 55 mph: 0.00005 and 0.00018 in CRR). The report
// measured the first with its force balance and the second from its accelerometers; taking the
// accelerometers' dissipation out of the force balance leaves the tires' own CRR, the figure a
// drum test (ISO 28580) would give.
#include <optional>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/vibration.hpp"

namespace roadload {

struct TireCrr {
  double crr = 0, sigma = 0, lo = 0, hi = 0;
  double dynamic_crr = 0;  // the dissipation as a coefficient of the weight: P / (v W)
};

// Nothing for a cell without a CRR, a speed or a weight. The interval has the confidence of the
// cell's own. `relative_error` is the dissipation's (docs/spectra.md: dampers within 3 %, tires
// within 4.4 % in the worst cell).
std::optional<TireCrr> tire_crr(const CellResult& cell, double dissipated_w, double relative_error = 0.05);

// The cells with their CRR and sigma replaced by the tires' own where the accelerometers measured
// the cell; the others keep the force balance's.
std::vector<CellResult> with_tire_crr(std::vector<CellResult> cells, const VibrationAnalysis& vibration);

}  // namespace roadload
