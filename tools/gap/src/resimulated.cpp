#include "resimulated.hpp"

#include <cmath>

namespace roadload::gap {

Eigen::VectorXd values(std::span<const RecordedRun> runs) {
  std::size_t n = 0;
  for (const auto& r : runs) n += r.features.features.size();
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  Eigen::Index i = 0;
  for (const auto& r : runs) {
    for (const auto& f : r.features.features) v(i++) = f.value;
  }
  return v;
}

Span span_of(const sim::EffectInfo& info, double base) {
  const double width = info.max - info.min;
  if (info.min < 0) return {info.min - 0.25 * width, info.max + 0.25 * width, info.max, info.min};
  return {0.0, info.max + 0.25 * width, info.max, 0.5 * (base + info.max) > 0 ? 0.5 * (base + info.max) : 0.5 * info.max};
}

namespace {

// Run r's re-simulation with its nominal truck moved by `shift_sigma`.
sim::Scenario on_truck(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, std::size_t r,
                       const std::vector<double>& shift_sigma) {
  sim::Scenario s = resims[r];
  for (std::size_t j = 0; j < shift_sigma.size() && j < lib.priors[r].size(); ++j) {
    const NominalPrior& prior = lib.priors[r][j];
    set_nominal(s, prior.id, prior.value + shift_sigma[j] * prior.sigma);
  }
  return s;
}

}  // namespace

std::vector<Eigen::VectorXd> resimulated(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims,
                                         const std::vector<Resimulation>& variants, const j1939::Database& db,
                                         const GapOptions& options) {
  std::vector<SimTask> tasks;
  for (const Resimulation& v : variants) {
    for (std::size_t r = 0; r < resims.size(); ++r) {
      sim::Scenario s = on_truck(lib, resims, r, v.shift_sigma);
      for (std::size_t i = 0; v.effects != nullptr && i < v.effects->effects.size(); ++i) {
        add_candidate(s, lib.responses[v.effects->effects[i]].effect, v.effects->magnitude_half0[i]);
      }
      tasks.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
    }
  }
  const std::vector<RecordedRun> sims = simulate_all(tasks, db, options.jobs);
  std::vector<Eigen::VectorXd> out;
  for (std::size_t k = 0; k < variants.size(); ++k) out.push_back(group_values(sims, k, resims.size()));
  return out;
}

Eigen::VectorXd resimulated(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const std::vector<double>& shift_sigma,
                            const Fit* effects, const j1939::Database& db, const GapOptions& options) {
  return resimulated(lib, resims, std::vector<Resimulation>{{shift_sigma, effects}}, db, options).front();
}

Fit refit_on_truck(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real, const Fit& chosen,
                   const std::vector<double>& shift_sigma, const Eigen::VectorXd& truck, const j1939::Database& db,
                   const GapOptions& options) {
  std::vector<SimTask> tasks;
  std::vector<Span> spans;
  for (std::size_t e : chosen.effects) {
    const auto& resp = lib.responses[e];
    spans.push_back(span_of(sim::effect_info(resp.effect), resp.base));
    for (double m : {spans.back().m1, spans.back().m2}) {
      for (std::size_t r = 0; r < resims.size(); ++r) {
        sim::Scenario s = on_truck(lib, resims, r, shift_sigma);
        add_candidate(s, resp.effect, m);
        tasks.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
      }
    }
  }
  const std::vector<RecordedRun> sims = simulate_all(tasks, db, options.jobs);
  auto group = [&](std::size_t g) { return group_values(sims, g, resims.size()); };
  Problem q;
  q.keys = lib.keys;
  q.z = (real - truck).cwiseQuotient(lib.sigma);
  std::vector<std::size_t> set;
  for (std::size_t i = 0; i < chosen.effects.size(); ++i) {
    const auto& resp = lib.responses[chosen.effects[i]];
    const sim::EffectInfo& info = sim::effect_info(resp.effect);
    Candidate c = Candidate::from_two(std::string(info.name), std::string(info.unit), resp.base, spans[i].lo, spans[i].hi,
                                      spans[i].m1, (group(2 * i) - truck).cwiseQuotient(lib.sigma), spans[i].m2,
                                      (group(2 * i + 1) - truck).cwiseQuotient(lib.sigma));
    c.realistic_lo = info.min;
    c.realistic_hi = info.max;
    q.candidates.push_back(std::move(c));
    set.push_back(i);
  }
  const Fit refit = fit_effects(q, set, options.rule);
  Fit out = chosen;
  for (std::size_t i = 0; i < set.size(); ++i) move_effect(out, i, refit.magnitude[i], refit.magnitude_half0[i]);
  return out;
}

}  // namespace roadload::gap
