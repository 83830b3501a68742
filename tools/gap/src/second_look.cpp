#include "second_look.hpp"

#include <cmath>

#include "resimulated.hpp"

namespace roadload::gap {
namespace {

// The library's responses about where `placed` stands: each effect's quadratic re-centred on its
// magnitude, the nominal columns as they are; z what its re-simulation left.
Problem around(const Problem& p, const Placed& placed, const Eigen::VectorXd& real, const Eigen::VectorXd& sigma) {
  Problem q;
  q.keys = p.keys;
  q.nominal = p.nominal;
  q.z = (real - placed.values).cwiseQuotient(sigma);
  if (!placed.effects) return q;
  for (std::size_t i = 0; i < placed.effects->effects.size(); ++i) {
    Candidate c = p.candidates[placed.effects->effects[i]];
    const double m = placed.effects->magnitude_half0[i];
    c.a += 2.0 * (m - c.base) * c.b;
    c.base = m;
    q.candidates.push_back(std::move(c));
  }
  return q;
}

// The step fitted on half 0: the truck's offsets moved, and the effects' magnitudes with them.
Placed stepped(const Problem& q, const Placed& from, const DecisionRule& rule) {
  Placed to = from;
  std::vector<std::size_t> set;
  std::vector<double> magnitudes;
  if (from.effects) {
    for (std::size_t i = 0; i < q.candidates.size(); ++i) set.push_back(i);
    const Fit refit = fit_effects(q, set, rule);
    magnitudes = refit.magnitude_half0;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const double moved = refit.magnitude_half0[i] - from.effects->magnitude_half0[i];
      to.effects->magnitude_half0[i] += moved;
      to.effects->magnitude[i] += moved;
      to.effects->lo[i] += moved;
      to.effects->hi[i] += moved;
    }
  }
  const NominalFit truck = fit_nominal(q, set, magnitudes);
  for (std::size_t j = 0; j < to.shift_sigma.size() && j < truck.shift_sigma.size(); ++j) to.shift_sigma[j] += truck.shift_sigma[j];
  return to;
}

double half0_chi2(const Problem& p, const Eigen::VectorXd& real, const Eigen::VectorXd& values, const Eigen::VectorXd& sigma) {
  const double r = rms((real - values).cwiseQuotient(sigma), p.keys, 0);
  return r * r;
}

}  // namespace

void second_look(const ModelLibrary& lib, const Problem& p, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real,
                 Placed& alone, Placed& with, const j1939::Database& db, const GapOptions& options) {
  Placed next_alone = stepped(around(p, alone, real, lib.sigma), alone, options.rule);
  Placed next_with = stepped(around(p, with, real, lib.sigma), with, options.rule);
  const std::vector<Eigen::VectorXd> sims = resimulated(
      lib, resims, std::vector<Resimulation>{{next_alone.shift_sigma, nullptr}, {next_with.shift_sigma, &*next_with.effects}}, db,
      options);
  next_alone.values = sims[0];
  next_with.values = sims[1];
  for (auto [side, next] : {std::pair{&alone, &next_alone}, std::pair{&with, &next_with}}) {
    if (half0_chi2(p, real, next->values, lib.sigma) < half0_chi2(p, real, side->values, lib.sigma)) *side = std::move(*next);
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
