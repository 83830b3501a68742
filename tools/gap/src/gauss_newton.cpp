#include "roadload/gap/diagnosis.hpp"

#include <cassert>

namespace roadload::gap {

Placement gauss_newton_step(const Problem& p, const Eigen::VectorXd& z, const Placement& from, const DecisionRule& rule) {
  assert(from.magnitude_half0.size() == from.effects.size());
  Problem q;
  q.keys = p.keys;
  q.nominal = p.nominal;
  q.z = z;
  std::vector<std::size_t> set;
  for (std::size_t i = 0; i < from.effects.size(); ++i) {
    Candidate c = p.candidates[from.effects[i]];
    const double m = from.magnitude_half0[i];
    c.a += 2.0 * (m - c.base) * c.b;
    c.base = m;
    q.candidates.push_back(std::move(c));
    set.push_back(i);
  }
  Placement to = from;
  if (!set.empty()) to.magnitude_half0 = fit_effects(q, set, rule).magnitude_half0;
  const NominalFit truck = fit_nominal(q, set, to.magnitude_half0);
  for (std::size_t j = 0; j < to.shift_sigma.size() && j < truck.shift_sigma.size(); ++j) to.shift_sigma[j] += truck.shift_sigma[j];
  return to;
}

}  // namespace roadload::gap
