#include "roadload/gap/diagnosis.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

namespace roadload::gap {
namespace {

constexpr std::uint8_t kBothHalves = 255;

bool in_half(const FeatureKey& k, std::uint8_t half) { return half == kBothHalves || k.half == half; }

// The chi-square of z minus a candidate set's response and the nominal parameters' as a function
// of the magnitudes' offsets u from base and the nominal offsets t (in prior sigmas), over one
// half: zz - 2 c'h + c'Gc with c = (u1, u1^2, u2, u2^2, ..., t). For given u the best t is linear
// (with its unit prior), so a fit searches over u alone.
struct Quadratic {
  Eigen::MatrixXd g;
  Eigen::VectorXd h;
  double zz = 0;
  std::size_t n = 0;
  Eigen::Index ne = 0, nn = 0;                // effect and nominal columns
  Eigen::LDLT<Eigen::MatrixXd> nominal_info;  // G_nn + I: the nominal block with its prior
  std::optional<Eigen::VectorXd> kept;        // the nominal offsets, when held rather than fitted

  Quadratic(const Problem& p, const std::vector<std::size_t>& set, std::uint8_t half) {
    ne = static_cast<Eigen::Index>(2 * set.size());
    nn = static_cast<Eigen::Index>(p.nominal.size());
    Eigen::MatrixXd basis(p.z.size(), ne + nn);
    for (std::size_t i = 0; i < set.size(); ++i) {
      basis.col(static_cast<Eigen::Index>(2 * i)) = p.candidates[set[i]].a;
      basis.col(static_cast<Eigen::Index>(2 * i + 1)) = p.candidates[set[i]].b;
    }
    for (Eigen::Index j = 0; j < nn; ++j) basis.col(ne + j) = p.nominal[static_cast<std::size_t>(j)].per_sigma;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index r = 0; r < p.z.size(); ++r) {
      if (std::isfinite(p.z(r)) && in_half(p.keys[static_cast<std::size_t>(r)], half)) rows.push_back(r);
    }
    Eigen::MatrixXd b(static_cast<Eigen::Index>(rows.size()), ne + nn);
    Eigen::VectorXd z(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      b.row(static_cast<Eigen::Index>(i)) = basis.row(rows[i]);
      z(static_cast<Eigen::Index>(i)) = p.z(rows[i]);
    }
    g = b.transpose() * b;
    h = b.transpose() * z;
    zz = z.squaredNorm();
    n = rows.size();
    nominal_info.compute(g.bottomRightCorner(nn, nn) + Eigen::MatrixXd::Identity(nn, nn));
  }
  Eigen::VectorXd effect_coeffs(const std::vector<double>& u) const {
    Eigen::VectorXd c(ne);
    for (std::size_t i = 0; i < u.size(); ++i) {
      c(static_cast<Eigen::Index>(2 * i)) = u[i];
      c(static_cast<Eigen::Index>(2 * i + 1)) = u[i] * u[i];
    }
    return c;
  }
  // The nominal offsets that fit best beside the effect coefficients ce, or those kept.
  Eigen::VectorXd theta(const Eigen::VectorXd& ce) const {
    if (kept) return *kept;
    if (nn == 0) return {};
    return nominal_info.solve(h.tail(nn) - g.bottomLeftCorner(nn, ne) * ce);
  }
  double misfit(const Eigen::VectorXd& ce, const Eigen::VectorXd& t) const {
    Eigen::VectorXd c(ne + nn);
    c << ce, t;
    return zz - 2.0 * c.dot(h) + c.dot(g * c);
  }
  // What a fit minimises: the misfit with the best nominal offsets, plus their prior.
  double sse(const std::vector<double>& u) const {
    const Eigen::VectorXd ce = effect_coeffs(u);
    const Eigen::VectorXd t = theta(ce);
    return misfit(ce, t) + t.squaredNorm();
  }
  // This half's misfit at u with the nominal offsets another half's fit chose for u.
  double judged(const Quadratic& fit, const std::vector<double>& u) const {
    const Eigen::VectorXd ce = effect_coeffs(u);
    return misfit(ce, fit.theta(ce));
  }
  // From here on the truck stays where it fits without any effect.
  void keep_truck_alone() { kept = theta(Eigen::VectorXd::Zero(ne)); }
};

// Minimises along one coordinate within [lo, hi]: a grid, then golden section around its best.
double line_minimum(const Quadratic& q, std::vector<double>& u, std::size_t i, double lo, double hi) {
  constexpr int kGrid = 200;
  auto at = [&](double x) {
    u[i] = x;
    return q.sse(u);
  };
  double best_x = lo, best = at(lo);
  for (int k = 1; k <= kGrid; ++k) {
    const double x = lo + (hi - lo) * k / kGrid;
    if (const double v = at(x); v < best) best = v, best_x = x;
  }
  double a = std::max(lo, best_x - (hi - lo) / kGrid), b = std::min(hi, best_x + (hi - lo) / kGrid);
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < 40; ++k) {
    const double x1 = b - r * (b - a), x2 = a + r * (b - a);
    if (at(x1) < at(x2)) {
      b = x2;
    } else {
      a = x1;
    }
  }
  const double x = 0.5 * (a + b);
  if (at(x) < best) best_x = x;
  u[i] = best_x;
  return at(best_x);
}

// Offsets from base minimising the chi-square; coordinate descent for two effects.
std::vector<double> minimise(const Problem& p, const std::vector<std::size_t>& set, const Quadratic& q) {
  std::vector<double> u(set.size(), 0.0);
  const int rounds = set.size() == 1 ? 1 : 6;
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t i = 0; i < set.size(); ++i) {
      const Candidate& c = p.candidates[set[i]];
      line_minimum(q, u, i, c.lo - c.base, c.hi - c.base);
    }
  }
  return u;
}

// The chi-square each half's fit removes from the other half, both folds, minus the penalty; u0 is
// half 0's fit.
double held_out_gain(const Problem& p, const std::vector<std::size_t>& set, const std::array<Quadratic, 2>& half, double penalty,
                     std::vector<double>* u0 = nullptr) {
  double gain = 0;
  const std::vector<double> none(set.size(), 0.0);
  for (std::size_t fit = 0; fit < 2; ++fit) {
    const std::vector<double> u = minimise(p, set, half[fit]);
    gain += half[1 - fit].judged(half[fit], none) - half[1 - fit].judged(half[fit], u);
    if (fit == 0 && u0 != nullptr) *u0 = u;
  }
  return gain - penalty;
}

Fit fit_set(const Problem& p, const std::vector<std::size_t>& set, const DecisionRule& rule) {
  Fit f;
  f.effects = set;
  const double penalty = rule.penalty * static_cast<double>(set.size());
  std::array<Quadratic, 2> half = {Quadratic(p, set, 0), Quadratic(p, set, 1)};
  std::vector<double> u0;
  f.gain = held_out_gain(p, set, half, penalty, &u0);
  const Quadratic all(p, set, kBothHalves);
  const std::vector<double> u = minimise(p, set, all);
  // Interval from the curvature (Fisher information of unit-variance residuals, the nominal
  // parameters moving beside the effects with their prior), widened by the fit's own scatter when
  // it exceeds the noise model's.
  const auto k = static_cast<Eigen::Index>(set.size());
  const auto nn = static_cast<Eigen::Index>(p.nominal.size());
  Eigen::MatrixXd jac(p.z.size(), k + nn);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Candidate& c = p.candidates[set[static_cast<std::size_t>(i)]];
    jac.col(i) = c.a + 2.0 * u[static_cast<std::size_t>(i)] * c.b;
  }
  for (Eigen::Index j = 0; j < nn; ++j) jac.col(k + j) = p.nominal[static_cast<std::size_t>(j)].per_sigma;
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(k + nn, k + nn);
  info.bottomRightCorner(nn, nn).setIdentity();
  for (Eigen::Index r = 0; r < p.z.size(); ++r) {
    if (std::isfinite(p.z(r))) info += jac.row(r).transpose() * jac.row(r);
  }
  const double dof = std::max(1.0, static_cast<double>(all.n) - static_cast<double>(k));
  const double scale = std::max(1.0, all.sse(u) / dof);
  const Eigen::MatrixXd cov = info.ldlt().solve(Eigen::MatrixXd::Identity(k + nn, k + nn)) * scale;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Candidate& c = p.candidates[set[i]];
    const double m = c.base + u[i];
    const double half_width = 1.645 * std::sqrt(std::max(0.0, cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i))));
    f.magnitude.push_back(m);
    f.lo.push_back(m - half_width);
    f.hi.push_back(m + half_width);
    f.magnitude_half0.push_back(c.base + u0[i]);
    const double width = c.realistic_hi - c.realistic_lo;
    if (std::isfinite(width) && width > 0) {
      const double outside = std::max({0.0, c.realistic_lo - m, m - c.realistic_hi}) / width / rule.range_tolerance;
      f.plausibility *= std::exp(-outside * outside);
    }
  }
  // The truck the effects were fitted beside: an effect that fits only beside a truck farther out
  // than the spreads draw and than the truck fitted alone is taking up what the truck's linear
  // model cannot, not explaining the drive. One that brings a runaway truck back is not.
  const Eigen::VectorXd t = all.theta(all.effect_coeffs(u));
  const Eigen::VectorXd alone = all.theta(Eigen::VectorXd::Zero(all.ne));
  double most_beyond = 0;
  for (Eigen::Index j = 0; j < t.size(); ++j) {
    const double beyond = std::max(0.0, std::abs(t(j)) - std::max(rule.truck_sigmas, std::abs(alone(j))));
    f.truck_plausibility *= std::exp(-beyond * beyond);
    if (beyond > most_beyond || (most_beyond == 0 && std::abs(t(j)) > f.truck_sigma)) f.truck_sigma = std::abs(t(j));
    most_beyond = std::max(most_beyond, beyond);
  }
  // What the effects explain with the truck left where it fits alone needs no truck beyond it at all.
  if (f.truck_plausibility < 1) {
    for (Quadratic& q : half) q.keep_truck_alone();
    f.gain_truck_kept = held_out_gain(p, set, half, penalty);
  }
  if (f.gain > 0) {
    const double kept = std::min(f.gain, f.gain_truck_kept), scaled = f.gain * f.truck_plausibility;
    f.scored_truck_kept = kept > scaled;
    f.gain = f.plausibility * std::max(kept, scaled);
  }
  return f;
}

}  // namespace

Candidate Candidate::from_two(std::string name, std::string unit, double base, double lo, double hi, double m1,
                              const Eigen::VectorXd& d1, double m2, const Eigen::VectorXd& d2) {
  Candidate c;
  c.name = std::move(name);
  c.unit = std::move(unit);
  c.base = base;
  c.lo = lo;
  c.hi = hi;
  const double u1 = m1 - base, u2 = m2 - base;
  const double det = u1 * u2 * (u2 - u1);
  // Solve a u + b u^2 = d at u1 and u2; a feature either run missed moves by nothing.
  const Eigen::VectorXd e1 = d1.unaryExpr([](double v) { return std::isfinite(v) ? v : 0.0; });
  const Eigen::VectorXd e2 = d2.unaryExpr([](double v) { return std::isfinite(v) ? v : 0.0; });
  c.a = (e1 * u2 * u2 - e2 * u1 * u1) / det;
  c.b = (e2 * u1 - e1 * u2) / det;
  return c;
}

Eigen::VectorXd Candidate::response(double magnitude) const {
  const double u = magnitude - base;
  return a * u + b * (u * u);
}

std::vector<WhereItem> locate(const std::vector<FeatureKey>& keys, const Eigen::VectorXd& z, std::size_t limit) {
  std::map<std::pair<std::string, std::string>, WhereItem> groups;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const double v = z(static_cast<Eigen::Index>(i));
    if (!std::isfinite(v)) continue;
    WhereItem& w = groups[{keys[i].run, keys[i].channel}];
    w.run = keys[i].run;
    w.channel = keys[i].channel;
    w.features += 1;
    w.excess += v * v - 1.0;
    if (std::abs(v) > std::abs(w.worst_z)) {
      w.worst_z = v;
      w.worst_where = keys[i].where;
    }
  }
  std::vector<WhereItem> out;
  for (auto& [key, w] : groups) {
    w.significance = w.excess / std::sqrt(2.0 * static_cast<double>(w.features));
    out.push_back(w);
  }
  std::sort(out.begin(), out.end(), [](const WhereItem& x, const WhereItem& y) { return x.significance > y.significance; });
  if (out.size() > limit) out.resize(limit);
  return out;
}

double rms(const Eigen::VectorXd& z, const std::vector<FeatureKey>& keys, std::uint8_t half) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const double v = z(static_cast<Eigen::Index>(i));
    if (!std::isfinite(v) || !in_half(keys[i], half)) continue;
    sum += v * v;
    ++n;
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

Fit fit_effects(const Problem& p, const std::vector<std::size_t>& set, const DecisionRule& rule) { return fit_set(p, set, rule); }

NominalFit fit_nominal(const Problem& p, const std::vector<std::size_t>& set, const std::vector<double>& magnitude_half0) {
  NominalFit out;
  const Quadratic q0(p, set, 0), q1(p, set, 1);
  std::vector<double> u;
  for (std::size_t i = 0; i < set.size(); ++i) u.push_back(magnitude_half0[i] - p.candidates[set[i]].base);
  const Eigen::VectorXd ce = q0.effect_coeffs(u);
  const Eigen::VectorXd t = q0.theta(ce);
  out.chi2_half1_before = q1.misfit(q1.effect_coeffs(std::vector<double>(set.size(), 0.0)), Eigen::VectorXd::Zero(q1.nn));
  out.chi2_half1_after = q1.misfit(ce, t);
  if (q0.nn == 0) return out;
  const double dof = std::max(1.0, static_cast<double>(q0.n) - static_cast<double>(set.size()));
  const Eigen::MatrixXd cov = q0.nominal_info.solve(Eigen::MatrixXd::Identity(q0.nn, q0.nn)) * std::max(1.0, q0.sse(u) / dof);
  for (Eigen::Index j = 0; j < q0.nn; ++j) {
    const NominalColumn& c = p.nominal[static_cast<std::size_t>(j)];
    const double half_width = 1.645 * std::sqrt(std::max(0.0, cov(j, j))) * c.sigma;
    out.value.push_back(c.value + t(j) * c.sigma);
    out.lo.push_back(out.value.back() - half_width);
    out.hi.push_back(out.value.back() + half_width);
    out.shift_sigma.push_back(t(j));
  }
  return out;
}

double rival_margin(const Candidate& named, const Candidate& other, const DecisionRule& rule) {
  return std::max({rule.null_gain, named.null_gain, other.null_gain});
}

namespace {

// The single fits beyond twice their own noise that came within rival_margin() of the first chosen
// effect's own; the chosen effects and those a nominal parameter stands for left out. A rival
// need not clear the rule's gain: beside an effect named just past it, one just short of it is
// as likely.
std::vector<Fit> rivals(const Problem& p, const Diagnosis& d, const DecisionRule& rule) {
  const std::vector<std::size_t>& chosen = d.chosen->effects;
  const auto first = std::find_if(d.singles.begin(), d.singles.end(), [&](const Fit& f) { return f.effects[0] == chosen[0]; });
  std::vector<Fit> out;
  for (const Fit& f : d.singles) {
    const Candidate& c = p.candidates[f.effects[0]];
    if (std::find(chosen.begin(), chosen.end(), f.effects[0]) != chosen.end() || !c.stood_for_by.empty()) continue;
    const bool beyond_noise = f.gain > 0 && f.gain >= rule.null_factor * c.null_gain;
    if (beyond_noise && f.gain >= first->gain - rival_margin(p.candidates[chosen[0]], c, rule)) out.push_back(f);
  }
  return out;
}

}  // namespace

Diagnosis diagnose(const Problem& p, const DecisionRule& rule) {
  Diagnosis d;
  for (Eigen::Index r = 0; r < p.z.size(); ++r) {
    if (!std::isfinite(p.z(r))) continue;
    d.chi2 += p.z(r) * p.z(r);
    ++d.features;
  }
  d.where = locate(p.keys, p.z, 8);
  d.nominal = fit_nominal(p, {}, {});
  // Only places beyond the noise: two standard deviations of the group's chi-square.
  std::erase_if(d.where, [](const WhereItem& w) { return w.significance < 2.0; });
  for (std::size_t i = 0; i < p.candidates.size(); ++i) d.singles.push_back(fit_set(p, {i}, rule));
  std::sort(d.singles.begin(), d.singles.end(), [](const Fit& x, const Fit& y) { return x.gain > y.gain; });
  // Candidates a nominal parameter stands for are fitted and listed, never named or paired.
  std::vector<std::size_t> nameable;
  for (const Fit& f : d.singles) {
    if (p.candidates[f.effects[0]].stood_for_by.empty()) nameable.push_back(f.effects[0]);
  }
  const auto named = std::find_if(d.singles.begin(), d.singles.end(), [&](const Fit& f) {
    const Candidate& c = p.candidates[f.effects[0]];
    return c.stood_for_by.empty() && f.gain >= std::max(rule.null_gain, rule.null_factor * c.null_gain);
  });
  // A second effect extends the first: paired with the single that is named (else the best), the
  // others of the pool are tried. Two other effects that together beat it are no evidence against
  // it: two magnitudes more take up what the nominal truck's fit left, whatever the effect.
  if (!nameable.empty()) {
    const std::size_t first = named != d.singles.end() ? named->effects[0] : nameable.front();
    const std::size_t pool = std::min(rule.pair_pool, nameable.size());
    for (std::size_t j = 0; j < pool; ++j) {
      if (nameable[j] == first) continue;
      Fit f = fit_set(p, {first, nameable[j]}, rule);
      if (!d.best_pair || f.gain > d.best_pair->gain) d.best_pair = std::move(f);
    }
  }
  if (named == d.singles.end()) return d;
  d.chosen = *named;
  // A second effect must beat the first by more than the residual the first leaves unexplained
  // would grant by chance: the threshold grows with that residual's excess over the noise.
  // That residual is what the calibrated nominal truck leaves.
  const double calibrated = Quadratic(p, {}, kBothHalves).sse({});
  const double dispersion = std::max(1.0, (calibrated - d.chosen->gain) / static_cast<double>(std::max<std::size_t>(1, d.features)));
  const double needed = std::max(rule.pair_gain * dispersion, rule.pair_share * d.chosen->gain);
  // Its first member is the named single (fit_set keeps the order), which the answer, its rivals
  // and the bench's score read as the effect named.
  if (d.best_pair && d.best_pair->gain - d.chosen->gain > needed) d.chosen = *d.best_pair;
  d.rivals = rivals(p, d, rule);
  // The nominal truck as fitted beside the chosen effects; its held-out figures stay those of the
  // nominal calibration alone.
  const NominalFit joint = fit_nominal(p, d.chosen->effects, d.chosen->magnitude_half0);
  d.nominal.value = joint.value;
  d.nominal.lo = joint.lo;
  d.nominal.hi = joint.hi;
  d.nominal.shift_sigma = joint.shift_sigma;
  return d;
}

}  // namespace roadload::gap
