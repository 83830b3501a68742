#include "roadload/torque_scale_consider.hpp"

#include <cmath>
#include <string>

#include "roadload/identification.hpp"

namespace roadload {
namespace {

void widen_cell(CellResult& c, const CellResult& shifted, const AnalyzerConfig& cfg, const std::vector<std::string>& drive) {
  if (c.samples == 0 || shifted.samples == 0) return;
  c.crr_sigma = std::hypot(c.crr_sigma, shifted.crr - c.crr);
  c.crr_lo = c.crr - cfg.interval_z * c.crr_sigma;
  c.crr_hi = c.crr + cfg.interval_z * c.crr_sigma;
  judge_cell(c, cfg.filter.identified_crr_sigma, cfg.identification, drive);
}

}  // namespace

DriveAnalysis widen_by_shift(DriveAnalysis held, const DriveAnalysis& shifted, const AnalyzerConfig& cfg) {
  TripResult& t = held.trip;
  t.crr_sigma = std::hypot(t.crr_sigma, shifted.trip.crr - t.crr);
  t.mass_sigma_kg = std::hypot(t.mass_sigma_kg, shifted.trip.mass_kg - t.mass_kg);
  t.not_identified = trip_failures(t, t.usable_ticks > 0, cfg.filter.identified_crr_sigma, cfg.identification);
  t.identified = t.not_identified.empty();
  const std::vector<std::string> drive = drive_failures(t, cfg.identification);
  for (std::size_t i = 0; i < held.cells.size() && i < shifted.cells.size(); ++i) {
    widen_cell(held.cells[i], shifted.cells[i], cfg, drive);
  }
  for (std::size_t i = 0; i < held.pavements.size() && i < shifted.pavements.size(); ++i) {
    widen_cell(held.pavements[i].crr, shifted.pavements[i].crr, cfg, drive);
  }
  return held;
}

DriveAnalysis analyse_with_torque_scale(const AnalyzerConfig& cfg,
                                        const std::function<DriveAnalysis(const AnalyzerConfig&, TorqueScaleRun)>& analyze) {
  const double sigma = cfg.filter.truck.torque_scale_sigma;
  if (!(sigma > 0)) return analyze(cfg, TorqueScaleRun::held);
  AnalyzerConfig held = cfg;
  held.filter.truck.torque_scale_sigma = 0;
  AnalyzerConfig shifted = held;
  shifted.filter.torque_scale_held = cfg.filter.torque_scale_held + sigma;
  shifted.filter.truck.cda_prior_m2 += cfg.filter.truck.cda_per_torque_scale_m2 * sigma;
  DriveAnalysis nominal = analyze(held, TorqueScaleRun::held);  // first: a reader may be read once
  return widen_by_shift(std::move(nominal), analyze(shifted, TorqueScaleRun::shifted), held);
}

}  // namespace roadload
