#pragma once
// EEC1's torque scale carried into the intervals without shaping the filter's gains. As a
// considered state of the filter (Schmidt) its prior enters every gain: on hills, where the scale
// and the mass move the force alike, a wider prior leaves the mass less told by the grades and the
// cells further off (docs/journal.md, 2026-11-26). Instead the drive is analysed with the scale
// held exact, then again with it one prior sigma off: the scale is one constant over the drive,
// so each estimate's shift is its one-sigma error from the scale, mass and all, and adds to its
// variance. A consider analysis by finite difference, as the aero calibration takes its cells'
// sensitivities.
#include <functional>
#include <vector>

#include "roadload/drive_analyzer.hpp"

namespace roadload {

struct DriveAnalysis {
  std::vector<CellResult> cells;
  TripResult trip;
  std::vector<PavementResult> pavements;  // widened like the cells
};

enum class TorqueScaleRun { held, shifted };

// `analyze` runs the whole drive under a configuration; the shifted run needs only the force
// balance (no accelerometers). Without a torque prior, the one run as given.
DriveAnalysis analyse_with_torque_scale(const AnalyzerConfig& cfg,
                                        const std::function<DriveAnalysis(const AnalyzerConfig&, TorqueScaleRun)>& analyze);

// The held run's estimates, each sigma widened by the shifted run's shift of it and the
// identification checks run again on the wider intervals. The trip's drive checks are the held
// run's.
DriveAnalysis widen_by_shift(DriveAnalysis held, const DriveAnalysis& shifted, const AnalyzerConfig& cfg);

}  // namespace roadload
