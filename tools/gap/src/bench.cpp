#include "roadload/gap/bench.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "roadload/gap/nominal.hpp"
#include "roadload/gap/unseen.hpp"

namespace roadload::gap {
namespace {

std::vector<RealRun> drive(const BenchCase& c, const BenchDay& day, const j1939::Database& db, unsigned jobs) {
  std::vector<RunLayout> layouts;
  for (const auto& d : day.drives) layouts.push_back(layout_for(d.route));
  std::vector<SimTask> tasks;
  for (std::size_t r = 0; r < day.drives.size(); ++r) {
    sim::Scenario s = day.drives[r];
    for (const auto& [effect, magnitude] : c.effects) s.effects.set(effect, magnitude);
    drive_truck(s, nominal_priors(day.drives[r]), c.truck);
    tasks.push_back({std::move(s), c.seed * 16 + r, &layouts[r]});
  }
  std::vector<RecordedRun> recorded = simulate_all(tasks, db, jobs);
  std::vector<RealRun> runs;
  for (std::size_t r = 0; r < recorded.size(); ++r) runs.push_back({day.labels[r], day.models[r], std::move(recorded[r]), {}});
  return runs;
}

// Whether a day's roads give the effect something to act on: joints and slabs need jointed concrete.
bool day_shows(const BenchDay& day, sim::Effect e) {
  if (e != sim::Effect::joint_faulting && e != sim::Effect::slab_curl) return true;
  return std::any_of(day.models.begin(), day.models.end(), [](const sim::Scenario& m) {
    return std::any_of(m.route.cells.begin(), m.route.cells.end(), [](const auto& c) { return c.joint_spacing_m > 0; });
  });
}

}  // namespace

std::vector<sim::Effect> observable_effects() {
  std::vector<sim::Effect> out;
  for (const auto& e : sim::effect_catalog()) {
    if (!unobservable(e.id)) out.push_back(e.id);
  }
  return out;
}

const char* unobservable(sim::Effect e) {
  if (const char* why = unseen_by_features(e)) return why;
  switch (e) {
    case sim::Effect::mass_error:
      return "the nominal calibration's mass stands for it: a wrong declared mass is another truck's mass, scored in the "
             "nominal rows";
    case sim::Effect::air_density_error:
      return "the nominal calibration's CdA stands for it: air a constant share denser drags as a larger CdA does";
    default: return nullptr;
  }
}

std::vector<BenchCase> draw_cases(const BenchPlan& plan, const std::vector<BenchDay>& days) {
  std::mt19937_64 rng(plan.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<sim::Effect> pool = plan.effects;
  if (pool.empty()) pool = observable_effects();
  auto magnitude = [&](sim::Effect e, const BenchDay& day) {
    const sim::EffectInfo& info = sim::effect_info(e);
    const double base = day.models.front().effects.magnitude(e);
    const double keep_out = 0.25 * (info.max - info.min);
    for (;;) {
      const double m = info.min + unit(rng) * (info.max - info.min);
      if (std::abs(m - base) >= keep_out) return m;
    }
  };
  std::vector<BenchCase> cases;
  const auto nulls = static_cast<std::size_t>(std::lround(plan.null_share * static_cast<double>(plan.cases)));
  const auto pairs = static_cast<std::size_t>(std::lround(plan.pair_share * static_cast<double>(plan.cases)));
  for (std::size_t i = 0; i < plan.cases; ++i) {
    BenchCase c;
    c.seed = plan.seed * 100000 + i + 1;
    // Singles cycle through the pool so every effect is tried about equally often, each on a day
    // whose roads can show it.
    const bool null_run = i < nulls;
    const sim::Effect first = pool[(null_run ? 0 : i - nulls) % pool.size()];
    std::vector<std::size_t> eligible;
    for (std::size_t d = 0; d < days.size(); ++d) {
      if (null_run || day_shows(days[d], first)) eligible.push_back(d);
    }
    if (eligible.empty()) eligible.push_back(0);
    c.day = eligible[std::uniform_int_distribution<std::size_t>(0, eligible.size() - 1)(rng)];
    if (plan.draw_trucks) c.truck = draw_truck(nominal_priors(days[c.day].drives.front()).size(), rng);
    if (!null_run) {
      c.effects.emplace_back(first, magnitude(first, days[c.day]));
      std::vector<sim::Effect> seconds;
      for (sim::Effect e : pool) {
        if (e != first && day_shows(days[c.day], e)) seconds.push_back(e);
      }
      if (i >= plan.cases - pairs && !seconds.empty()) {
        const sim::Effect second =
            seconds[static_cast<std::size_t>(unit(rng) * static_cast<double>(seconds.size())) % seconds.size()];
        c.effects.emplace_back(second, magnitude(second, days[c.day]));
      }
    }
    cases.push_back(std::move(c));
  }
  std::shuffle(cases.begin(), cases.end(), rng);
  return cases;
}

CaseOutcome run_case(const BenchCase& c, const std::vector<BenchDay>& days, std::vector<ModelLibrary>& libraries,
                     const j1939::Database& db, const GapOptions& options) {
  const BenchDay& day = days[c.day];
  const std::vector<RealRun> runs = drive(c, day, db, options.jobs);
  const std::vector<sim::Scenario> resims = resimulations(runs);
  const ModelLibrary* lib = nullptr;
  for (const auto& l : libraries) {
    if (library_serves(l, resims)) lib = &l;
  }
  if (lib == nullptr) {
    // Built from a drive of its own, with no effect and a seed no case uses.
    BenchCase calibration{c.day, {}, c.seed + 7919, {}};
    libraries.push_back(build_library(drive(calibration, day, db, options.jobs), db, options));
    if (!library_serves(libraries.back(), resims)) libraries.back() = build_library(runs, db, options);
    lib = &libraries.back();
  }
  CaseOutcome o;
  o.truth = c;
  o.road = day.road;
  o.result = run_gap(*lib, runs, db, options);
  const std::vector<NominalPrior> priors = nominal_priors(day.drives.front());
  const NominalFit& fitted = o.result.diagnosis.nominal;
  for (std::size_t j = 0; j < priors.size() && j < fitted.value.size(); ++j) {
    const double truth = priors[j].value + (j < c.truck.size() ? c.truck[j] : 0.0) * priors[j].sigma;
    o.nominal_truth.push_back(truth);
    o.nominal_covered.push_back(fitted.lo[j] <= truth && truth <= fitted.hi[j]);
  }
  const auto& chosen = o.result.diagnosis.chosen;
  if (c.effects.empty()) {
    o.false_alarm = chosen.has_value();
    o.named_right = !chosen;
    return o;
  }
  auto hidden = [&](std::size_t candidate) {
    return std::any_of(c.effects.begin(), c.effects.end(),
                       [&](const auto& e) { return e.first == lib->responses[candidate].effect; });
  };
  if (chosen) {
    o.named_right = hidden(chosen->effects[0]);
    const auto& rivals = o.result.diagnosis.rivals;
    o.rival_right = !o.named_right && std::any_of(rivals.begin(), rivals.end(), [&](const Fit& f) { return hidden(f.effects[0]); });
  }
  o.visible = gap_visible(o.result);
  o.shrink = gap_shrink(o.result);
  return o;
}

std::string describe_effects(const std::vector<std::pair<sim::Effect, double>>& effects) {
  if (effects.empty()) return "none";
  std::string s;
  for (const auto& [e, m] : effects) {
    char text[96];
    std::snprintf(text, sizeof text, "%s%.*s=%.4g", s.empty() ? "" : " + ", static_cast<int>(sim::effect_info(e).name.size()),
                  sim::effect_info(e).name.data(), m);
    s += text;
  }
  return s;
}

void BenchScore::add(const CaseOutcome& o) {
  ++cases;
  right += o.named_right ? 1 : 0;
  by_road[o.road].first += o.named_right ? 1 : 0;
  by_road[o.road].second += 1;
  if (o.truth.effects.empty()) {
    ++nulls;
    alarms += o.false_alarm ? 1 : 0;
  }
  if (!o.truth.effects.empty() && o.result.diagnosis.chosen && !o.named_right) {
    ++wrong_names;
    rival_right += o.rival_right ? 1 : 0;
  }
  if (o.visible) {
    ++visible;
    shrink_sum += o.shrink;
  }
  const auto& d = o.result.diagnosis;
  for (std::size_t j = 0; j < o.nominal_truth.size(); ++j) {
    if (nominal.size() <= j) nominal.push_back({o.result.problem.nominal[j].name, o.result.problem.nominal[j].unit, 0, 0, 0, 0});
    Recovery& r = nominal[j];
    const double err = d.nominal.value[j] - o.nominal_truth[j];
    const double prior_err = o.result.problem.nominal[j].value - o.nominal_truth[j];
    r.cases += 1;
    r.covered += o.nominal_covered[j] ? 1 : 0;
    r.error_ss += err * err;
    r.prior_ss += prior_err * prior_err;
  }
  const std::string row = o.truth.effects.empty() ? "none"
                                                  : std::string(sim::effect_info(o.truth.effects.front().first).name) +
                                                        (o.truth.effects.size() > 1 ? " (+1)" : "");
  confusion[row][d.chosen ? o.result.problem.candidates[d.chosen->effects[0]].name : "none"] += 1;
}

std::string named_effects(const CaseOutcome& o) {
  const auto& chosen = o.result.diagnosis.chosen;
  if (!chosen) return "none";
  std::string s;
  for (std::size_t i = 0; i < chosen->effects.size(); ++i) {
    char text[96];
    std::snprintf(text, sizeof text, "%s%s=%.4g", i ? " + " : "", o.result.problem.candidates[chosen->effects[i]].name.c_str(),
                  chosen->magnitude[i]);
    s += text;
  }
  return s;
}

}  // namespace roadload::gap
