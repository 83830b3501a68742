#include "second_look.hpp"

#include <cmath>
#include <utility>

#include "resimulated.hpp"

namespace roadload::gap {
namespace {

// One step from where `from` stands (gauss_newton_step), its effects' other figures moved with
// their magnitudes.
Placed stepped(const Problem& p, const Placed& from, const Eigen::VectorXd& real, const Eigen::VectorXd& sigma,
               const DecisionRule& rule) {
  Placement at{from.shift_sigma, {}, {}};
  if (from.effects) at = {from.shift_sigma, from.effects->effects, from.effects->magnitude_half0};
  const Placement next = gauss_newton_step(p, (real - from.values).cwiseQuotient(sigma), at, rule);
  Placed to = from;
  to.shift_sigma = next.shift_sigma;
  for (std::size_t i = 0; to.effects && i < next.magnitude_half0.size(); ++i) {
    const double moved = next.magnitude_half0[i] - from.effects->magnitude_half0[i];
    move_effect(*to.effects, i, from.effects->magnitude[i] + moved, next.magnitude_half0[i]);
  }
  return to;
}

// Half 0's chi-square of each of two re-simulations, over the features both saw: a step that
// loses a feature must not gain by its absence.
std::pair<double, double> half0_chi2(const Problem& p, const Eigen::VectorXd& real, const Eigen::VectorXd& a,
                                     const Eigen::VectorXd& b, const Eigen::VectorXd& sigma) {
  const Eigen::VectorXd za = (real - a).cwiseQuotient(sigma), zb = (real - b).cwiseQuotient(sigma);
  double sa = 0, sb = 0;
  for (Eigen::Index i = 0; i < za.size(); ++i) {
    if (p.keys[static_cast<std::size_t>(i)].half != 0 || !std::isfinite(za(i)) || !std::isfinite(zb(i))) continue;
    sa += za(i) * za(i);
    sb += zb(i) * zb(i);
  }
  return {sa, sb};
}

}  // namespace

void second_look(const ModelLibrary& lib, const Problem& p, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real,
                 Placed& alone, Placed& with, const j1939::Database& db, const GapOptions& options) {
  Placed next_alone = stepped(p, alone, real, lib.sigma, options.rule);
  Placed next_with = stepped(p, with, real, lib.sigma, options.rule);
  const std::vector<Eigen::VectorXd> sims = resimulated(
      lib, resims, std::vector<Resimulation>{{next_alone.shift_sigma, nullptr}, {next_with.shift_sigma, &*next_with.effects}}, db,
      options);
  next_alone.values = sims[0];
  next_with.values = sims[1];
  for (auto [side, next] : {std::pair{&alone, &next_alone}, std::pair{&with, &next_with}}) {
    const auto [chi2_now, chi2_stepped] = half0_chi2(p, real, side->values, next->values, lib.sigma);
    if (chi2_stepped < chi2_now) *side = std::move(*next);
  }
}

void move_truck(NominalFit& fit, const std::vector<NominalColumn>& columns, const std::vector<double>& shift_sigma) {
  for (std::size_t j = 0; j < fit.value.size() && j < shift_sigma.size() && j < columns.size(); ++j) {
    const double moved = (shift_sigma[j] - fit.shift_sigma[j]) * columns[j].sigma;
    fit.value[j] += moved;
    fit.lo[j] += moved;
    fit.hi[j] += moved;
    fit.shift_sigma[j] = shift_sigma[j];
  }
}

}  // namespace roadload::gap
