#pragma once
// A second look before a name is withheld (engine.cpp). The truck and the effects were placed by
// the library's responses, taken about the model's truck; an effect that works with the truck
// nonlinearly (a driveline loss beside the engine's friction) can then re-simulate worse than the
// truck alone did although it is there. Each side, the truck alone and the truck with the effects,
// takes one Gauss-Newton step from its own re-simulation (the library's responses as the
// Jacobian, fitted on half 0) and keeps it only where half 0 fits better: the verdict on half 1
// then compares the two at their best, neither favoured.
#include <optional>
#include <vector>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

struct Placed {
  std::vector<double> shift_sigma;  // the truck, in prior sigmas off the model's
  std::optional<Fit> effects;       // at their magnitudes fitted on half 0; none: the truck alone
  Eigen::VectorXd values;           // the drives re-simulated with both
};

// Steps `alone` and `with` (re-simulating both at once) and keeps each step only where it lowers
// half 0's chi-square.
void second_look(const ModelLibrary& lib, const Problem& p, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real,
                 Placed& alone, Placed& with, const j1939::Database& db, const GapOptions& options);

// The answer's truck rows moved to `shift_sigma`, each interval's width kept.
void move_truck(NominalFit& fit, const std::vector<NominalColumn>& columns, const std::vector<double>& shift_sigma);

}  // namespace roadload::gap
