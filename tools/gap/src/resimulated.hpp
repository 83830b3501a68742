#pragma once
// Pieces the library and the diagnosis share (engine.cpp): features as one vector, the span of
// magnitudes an effect is simulated and fitted over, and the drives re-simulated with a fitted
// truck and effects.
#include <cstdint>
#include <span>
#include <vector>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// The re-simulations' own seed: the baseline and every response share it, so their differences
// hold the change alone.
inline constexpr std::uint64_t kBaselineSeed = 1;

// The recordings' features in the library's order. A recording may carry other sensors than the
// model's truck: what the model has and the recording lacks is missing (NaN), the rest is ignored.
Eigen::VectorXd aligned(const std::vector<RealRun>& runs, const ModelLibrary& lib);

// Every run's features, concatenated in order.
Eigen::VectorXd values(std::span<const RecordedRun> runs);
// Simulations made `runs` at a time (every run of one change, then the next change): group g's.
inline Eigen::VectorXd group_values(std::span<const RecordedRun> sims, std::size_t g, std::size_t runs) {
  return values(sims.subspan(g * runs, runs));
}

// Magnitudes the library simulates and a fit may take: the catalog's realistic range, widened by
// a quarter, reaching zero for an effect that cannot be negative.
struct Span {
  double lo, hi, m1, m2;
};
Span span_of(const sim::EffectInfo& info, double base);

// Effect i of `f` moved to new magnitudes (both halves, half 0), its interval keeping its widths.
inline void move_effect(Fit& f, std::size_t i, double magnitude, double magnitude_half0) {
  f.lo[i] += magnitude - f.magnitude[i];
  f.hi[i] += magnitude - f.magnitude[i];
  f.magnitude[i] = magnitude;
  f.magnitude_half0[i] = magnitude_half0;
}

// The drives re-simulated with the nominal truck moved by `shift_sigma` and, when given, the
// effects at their magnitudes fitted on half 0 (`magnitude_half0`).
Eigen::VectorXd resimulated(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const std::vector<double>& shift_sigma,
                            const Fit* effects, const j1939::Database& db, const GapOptions& options);
// Several such re-simulations at once, so that a single drive's keep both cores busy.
struct Resimulation {
  std::vector<double> shift_sigma;
  const Fit* effects = nullptr;
};
std::vector<Eigen::VectorXd> resimulated(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims,
                                         const std::vector<Resimulation>& variants, const j1939::Database& db,
                                         const GapOptions& options);

// The chosen effects refitted on half 0 around the truck fitted beside them: their responses
// simulated again on that truck, since an effect's size follows the truck's (drag that grows with
// yaw scales with CdA). Magnitudes move to the refit; intervals keep the joint fit's widths.
// `truck` is the drives re-simulated with that truck alone.
Fit refit_on_truck(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real, const Fit& chosen,
                   const std::vector<double>& shift_sigma, const Eigen::VectorXd& truck, const j1939::Database& db,
                   const GapOptions& options);

}  // namespace roadload::gap
