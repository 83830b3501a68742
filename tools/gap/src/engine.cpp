#include "roadload/gap/engine.hpp"

#include <random>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "noise_floor.hpp"
#include "resimulated.hpp"
#include "roadload/gap/unseen.hpp"
#include "roadload/numbers.hpp"
#include "second_look.hpp"

namespace roadload::gap {
namespace {

constexpr std::uint64_t kNoiseSeed0 = 1000;

void say(const GapOptions& o, const std::string& line) {
  if (o.progress) o.progress(line);
}

}  // namespace

void add_candidate(sim::Scenario& s, sim::Effect e, double magnitude) {
  switch (e) {
    case sim::Effect::mass_error: s.load_scale /= 1.0 + magnitude; return;
    case sim::Effect::air_density_error:
      // The simulator's station reads warm by d and 150 Pa per degree low (docs/simulator.md).
      s.weather.air_temp_c -= magnitude;
      s.weather.pressure_pa += 150.0 * magnitude;
      return;
    default: s.effects.set(e, magnitude);
  }
}

std::vector<sim::Scenario> resimulations(const std::vector<RealRun>& runs) {
  std::vector<sim::Scenario> out;
  for (const RealRun& r : runs) out.push_back(resimulation(r.model, r.recorded.features.conditions, r.recorded.meta));
  return out;
}

namespace {
std::vector<Candidate> candidates(const ModelLibrary& lib, const Eigen::VectorXd& model, const Eigen::VectorXd& yaw);
void set_null_gains(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals, const GapOptions& options);

// Noise drives: the model driven with seeds of its own and its own wandering wind, each a truck
// drawn from the nominal priors (its offsets in `trucks`), to be re-simulated from its recording
// exactly as a real drive is, so the floor holds every difference the pipeline makes when nothing
// but the truck is missing from the model.
std::vector<SimTask> noise_drive_tasks(const ModelLibrary& lib, std::size_t count, std::vector<std::vector<double>>& trucks) {
  std::vector<SimTask> tasks;
  for (std::size_t k = 0; k < count; ++k) {
    std::mt19937_64 rng(kNoiseSeed0 + k);
    const std::vector<double>& truck = trucks.emplace_back(draw_truck(lib.priors.front().size(), rng));
    for (std::size_t r = 0; r < lib.scenarios.size(); ++r) {
      sim::Scenario s = lib.scenarios[r];
      s.weather.wind_trace.clear();
      drive_truck(s, lib.priors[r], truck);
      tasks.push_back({std::move(s), kNoiseSeed0 + k, &lib.layouts[r]});
    }
  }
  return tasks;
}
}  // namespace

ModelLibrary build_library(const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options) {
  ModelLibrary lib;
  lib.scenarios = resimulations(runs);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    lib.labels.push_back(runs[r].label);
    lib.layouts.push_back(layout_for(runs[r].model.route));
    lib.priors.push_back(nominal_priors(lib.scenarios[r]));
  }
  const std::size_t n_runs = runs.size();
  std::vector<SimTask> tasks;
  auto add_all = [&](const std::function<void(sim::Scenario&)>& change, std::uint64_t seed) {
    for (std::size_t r = 0; r < n_runs; ++r) {
      sim::Scenario s = lib.scenarios[r];
      change(s);
      tasks.push_back({std::move(s), seed, &lib.layouts[r]});
    }
  };
  add_all([](sim::Scenario&) {}, kBaselineSeed);
  std::vector<std::vector<double>> trucks;
  const std::vector<SimTask> noise_drives = noise_drive_tasks(lib, options.noise_runs, trucks);
  say(options, "library: " + std::to_string(noise_drives.size()) + " noise drives");
  const std::vector<RecordedRun> noise = simulate_all(noise_drives, db, options.jobs, options.progress);
  for (std::size_t k = 0; k < options.noise_runs; ++k) {
    for (std::size_t r = 0; r < n_runs; ++r) {
      const RecordedRun& drive = noise[k * n_runs + r];
      tasks.push_back({resimulation(runs[r].model, drive.features.conditions, drive.meta), kBaselineSeed, &lib.layouts[r]});
    }
  }
  for (const sim::Effect effect : fitted_effects()) {
    const sim::EffectInfo& info = sim::effect_info(effect);
    const double base = lib.scenarios.front().effects.magnitude(info.id);
    const Span sp = span_of(info, base);
    lib.responses.push_back({info.id, base, sp.m1, sp.m2, {}, {}});
    add_all([&](sim::Scenario& s) { add_candidate(s, info.id, sp.m1); }, kBaselineSeed);
    add_all([&](sim::Scenario& s) { add_candidate(s, info.id, sp.m2); }, kBaselineSeed);
  }
  const std::size_t first_nominal = tasks.size() / n_runs;
  for (std::size_t j = 0; j < lib.priors.front().size(); ++j) {
    for (std::size_t r = 0; r < n_runs; ++r) {
      sim::Scenario s = lib.scenarios[r];
      set_nominal(s, lib.priors[r][j].id, lib.priors[r][j].value + lib.priors[r][j].sigma);
      tasks.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
    }
  }
  say(options, "library: " + std::to_string(tasks.size()) +
                   " simulations (baseline, the noise drives' re-simulations, 2 per fitted effect, 1 per nominal parameter)");
  const std::vector<RecordedRun> sims = simulate_all(tasks, db, options.jobs, options.progress);
  auto group = [&](std::size_t g) { return group_values(sims, g, n_runs); };
  const std::span<const RecordedRun> base = std::span(sims).first(n_runs);
  for (std::size_t r = 0; r < n_runs; ++r) {
    for (const Feature& f : base[r].features.features) {
      const auto half = options.holdout == Holdout::runs ? static_cast<std::uint8_t>(r % 2) : f.half;
      lib.keys.push_back({lib.labels[r], f.channel, f.where, half});
      lib.feature_half.push_back(f.half);
    }
  }
  lib.baseline = values(base);
  // Each noise drive's residual against its own re-simulation: the floor, then its chi-square.
  std::vector<Eigen::VectorXd> residuals;
  for (std::size_t k = 0; k < options.noise_runs; ++k) {
    residuals.push_back(group_values(noise, k, n_runs) - group(1 + k));
  }
  for (std::size_t e = 0; e < lib.responses.size(); ++e) {
    lib.responses[e].f1 = group(1 + options.noise_runs + 2 * e);
    lib.responses[e].f2 = group(2 + options.noise_runs + 2 * e);
  }
  std::vector<Eigen::VectorXd> plus_sigma;
  for (std::size_t j = 0; j < lib.priors.front().size(); ++j) plus_sigma.push_back(group(first_nominal + j));
  set_nominal_delta(lib, plus_sigma);
  set_noise_floor(lib, residuals, trucks);
  set_null_gains(lib, residuals, options);
  return lib;
}

namespace {

// What each candidate finds in the noise drives, fitted and scored as a real drive's would be
// (the library's own response for drag that grows with yaw).
void set_null_gains(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals, const GapOptions& options) {
  const auto yaw = std::find_if(lib.responses.begin(), lib.responses.end(),
                                [](const auto& r) { return r.effect == sim::Effect::yaw_drag; });
  lib.null_gain.assign(lib.responses.size(), 0.0);
  for (const Eigen::VectorXd& d : residuals) {
    Problem q;
    q.keys = lib.keys;
    q.z = d.cwiseQuotient(lib.sigma);
    q.candidates = candidates(lib, lib.baseline, yaw->f1);
    q.nominal = nominal_columns(lib, lib.sigma);
    for (std::size_t c = 0; c < q.candidates.size(); ++c) {
      lib.null_gain[c] = std::max(lib.null_gain[c], fit_effects(q, {c}, options.rule).gain);
    }
  }
}

}  // namespace

bool library_serves(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims) {
  if (resims.size() != lib.scenarios.size()) return false;
  for (std::size_t r = 0; r < resims.size(); ++r) {
    const sim::Scenario& a = lib.scenarios[r];
    const sim::Scenario& b = resims[r];
    if (a.route.name != b.route.name || a.start_m != b.start_m || a.end_m != b.end_m) return false;
    if (std::abs(a.speed_mps - b.speed_mps) > 0.3 || std::abs(a.load_scale - b.load_scale) > 0.08) return false;
    if (std::abs(a.weather.air_temp_c - b.weather.air_temp_c) > 6.0) return false;
    // The tires' warm-up left at the start, within a twentieth of their cold excess: at the largest
    // excess (0.5) that is 2.5 % of CRR, less than the 6 C allowed above moves a CRR with temperature.
    if (std::abs(sim::tire_warmup_left(a.driven_before) - sim::tire_warmup_left(b.driven_before)) > 0.05) return false;
    if (std::abs(a.weather.pressure_pa - b.weather.pressure_pa) > 2000.0) return false;  // as 6 C does to the air's density
    if (a.duration.has_value() != b.duration.has_value()) return false;
    if (a.duration && std::abs(a.duration->count() - b.duration->count()) > 0.05 * a.duration->count() + 5.0) return false;
    if (std::abs(a.weather.wind_speed_mps - b.weather.wind_speed_mps) > 1.5) return false;
    if (std::abs(std::remainder(a.weather.wind_from_deg - b.weather.wind_from_deg, 360.0)) > 30.0) return false;
  }
  return true;
}

namespace {
void held_out(GapResult& g, const Eigen::VectorXd& calibrated_z, const Eigen::VectorXd& after_z);
// Re-simulated, the chosen effects lower the held-out chi-square, and remove the rule's share of
// a visible gap.
bool borne_out(const GapResult& g, const DecisionRule& rule) {
  return g.chi2_after < g.chi2_before && (!gap_visible(g) || gap_shrink(g) >= rule.min_shrink);
}
struct Trucks {
  std::vector<double> alone, beside;  // fitted on half 0 alone and beside the chosen effects
};
void look_again(GapResult& g, const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real,
                Trucks& trucks, const j1939::Database& db, const GapOptions& options);
void withhold(GapResult& g, const Eigen::VectorXd& real, const ModelLibrary& lib, const std::vector<double>& alone_shift);

// A name withheld takes its rivals with it (they were rivals of that name), and the answer's truck
// rows become the truck fitted alone, at `alone_shift` when a second look moved it.
void unname(GapResult& g, const ModelLibrary& lib, const std::vector<double>& alone_shift = {}) {
  g.diagnosis.chosen.reset();
  g.diagnosis.rivals.clear();
  g.diagnosis.nominal = fit_nominal(g.problem, {}, {});
  widen_by_miss(g.diagnosis.nominal, lib, g.problem.nominal);
  move_truck(g.diagnosis.nominal, g.problem.nominal, alone_shift);
}
}  // namespace

GapResult run_gap(const ModelLibrary& lib, const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options) {
  const std::vector<sim::Scenario> resims = resimulations(runs);
  // Drag that grows with the yaw angle follows the crosswind the truck met, cell by cell: its
  // response is simulated on this drive's own wind rather than taken from the library's. It is
  // linear in its magnitude, so one simulation gives it (at the library's first magnitude),
  // simulated beside the drives themselves.
  const auto yaw_response = std::find_if(lib.responses.begin(), lib.responses.end(),
                                         [](const auto& r) { return r.effect == sim::Effect::yaw_drag; });
  std::vector<SimTask> tasks;
  for (std::size_t r = 0; r < runs.size(); ++r) tasks.push_back({resims[r], kBaselineSeed, &lib.layouts[r]});
  for (std::size_t r = 0; r < runs.size(); ++r) {
    sim::Scenario s = resims[r];
    add_candidate(s, sim::Effect::yaw_drag, yaw_response->m1);
    tasks.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
  }
  say(options, "re-simulating " + std::to_string(runs.size()) + " run(s)");
  const std::vector<RecordedRun> sims = simulate_all(tasks, db, options.jobs);
  const Eigen::VectorXd model = group_values(sims, 0, runs.size());
  const Eigen::VectorXd yaw = group_values(sims, 1, runs.size());
  const Eigen::VectorXd real = aligned(runs, lib);

  GapResult g;
  Problem& p = g.problem;
  p.keys = lib.keys;
  p.z = (real - model).cwiseQuotient(lib.sigma);
  p.candidates = candidates(lib, model, yaw);
  for (std::size_t c = 0; c < p.candidates.size() && c < lib.null_gain.size(); ++c) {
    p.candidates[c].null_gain = lib.null_gain[c];
    const auto nominal = stands_for(lib.responses[c].effect);
    const bool fitted = nominal && std::any_of(lib.priors.front().begin(), lib.priors.front().end(),
                                               [&](const NominalPrior& prior) { return prior.id == *nominal; });
    if (fitted) p.candidates[c].stood_for_by = std::string(nominal_name(*nominal));
  }
  p.nominal = nominal_columns(lib, lib.sigma);
  say(options, "fitting " + std::to_string(p.candidates.size()) + " candidate effects and their pairs");
  g.diagnosis = diagnose(p, options.rule);
  widen_by_miss(g.diagnosis.nominal, lib, p.nominal);
  for (const RealRun& run : runs) {
    if (run.caveat.empty()) continue;
    g.withheld += (g.withheld.empty() ? "" : "; ") + run.label + ": " + run.caveat;
  }
  if (!g.withheld.empty()) unname(g, lib);

  g.null_chi2_mean = lib.null_chi2_mean;
  g.null_chi2_sd = lib.null_chi2_sd;
  g.real = real;
  g.model = model;
  g.sigma = lib.sigma;
  say(options, "re-simulating with the nominal truck fitted on half 0");
  // The truck fitted beside the chosen effect is re-simulated with the truck fitted alone.
  const std::vector<double> shift = g.diagnosis.nominal.shift_sigma;
  const std::vector<double> alone_shift = fit_nominal(p, {}, {}).shift_sigma;
  std::vector<Resimulation> variants{{alone_shift, nullptr}};
  if (g.diagnosis.chosen) variants.push_back({shift, nullptr});
  const std::vector<Eigen::VectorXd> trucks = resimulated(lib, resims, variants, db, options);
  g.calibrated = trucks.front();
  g.after = g.calibrated;
  if (g.diagnosis.chosen) {
    say(options, "refitting the chosen effect on the fitted truck, then re-simulating with both (fitted on half 0)");
    const Eigen::VectorXd& truck = trucks.back();
    g.diagnosis.chosen = refit_on_truck(lib, resims, real, *g.diagnosis.chosen, shift, truck, db, options);
    g.after = resimulated(lib, resims, shift, &*g.diagnosis.chosen, db, options);
  }
  held_out(g, (real - g.calibrated).cwiseQuotient(lib.sigma), (real - g.after).cwiseQuotient(lib.sigma));
  Trucks fitted{alone_shift, shift};
  if (g.diagnosis.chosen && !borne_out(g, options.rule)) look_again(g, lib, resims, real, fitted, db, options);
  // The fit predicted the held-out residual from linear responses; the re-simulation with the
  // effect must bear it out. A name the simulator does not confirm is withheld, not reported.
  if (g.diagnosis.chosen && !borne_out(g, options.rule)) withhold(g, real, lib, fitted.alone);
  g.unmatched = unmatched_channels(runs, lib);
  return g;
}

namespace {

// Each effect as a candidate: its response from the library's two magnitudes, or, for drag that
// grows with yaw, from this drive's own wind (`yaw`).
std::vector<Candidate> candidates(const ModelLibrary& lib, const Eigen::VectorXd& model, const Eigen::VectorXd& yaw) {
  std::vector<Candidate> out;
  for (const auto& resp : lib.responses) {
    const sim::EffectInfo& info = sim::effect_info(resp.effect);
    const Span sp = span_of(info, resp.base);
    Eigen::VectorXd d1 = (resp.f1 - lib.baseline).cwiseQuotient(lib.sigma);
    Eigen::VectorXd d2 = (resp.f2 - lib.baseline).cwiseQuotient(lib.sigma);
    if (resp.effect == sim::Effect::yaw_drag) {
      d1 = (yaw - model).cwiseQuotient(lib.sigma);
      d2 = d1 * ((resp.m2 - resp.base) / (resp.m1 - resp.base));
    }
    Candidate c = Candidate::from_two(std::string(info.name), std::string(info.unit), resp.base, sp.lo, sp.hi, resp.m1, d1, resp.m2,
                                      d2);
    c.realistic_lo = info.min;
    c.realistic_hi = info.max;
    out.push_back(std::move(c));
  }
  return out;
}

// The re-simulation with the chosen effects did not bear them out: one step more
// for the truck alone and for the truck with them (second_look.hpp), then the verdict again.
void look_again(GapResult& g, const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Eigen::VectorXd& real,
                Trucks& trucks, const j1939::Database& db, const GapOptions& options) {
  say(options,
      "re-simulated, the effect does not lower the held-out residual by its share: one step more for the truck alone and "
      "with it");
  Placed alone{trucks.alone, std::nullopt, g.calibrated}, with{trucks.beside, g.diagnosis.chosen, g.after};
  second_look(lib, g.problem, resims, real, alone, with, db, options);
  g.calibrated = alone.values;
  g.after = with.values;
  g.diagnosis.chosen = with.effects;
  move_truck(g.diagnosis.nominal, g.problem.nominal, with.shift_sigma);
  trucks.alone = alone.shift_sigma;
  held_out(g, (real - g.calibrated).cwiseQuotient(lib.sigma), (real - g.after).cwiseQuotient(lib.sigma));
}

// Nothing named: the answer's truck rows are the truck fitted alone, where the re-simulation left it.
void withhold(GapResult& g, const Eigen::VectorXd& real, const ModelLibrary& lib, const std::vector<double>& alone_shift) {
  char why[320];
  const char* name = g.problem.candidates[g.diagnosis.chosen->effects[0]].name.c_str();
  if (g.chi2_after >= g.chi2_before) {
    std::snprintf(why, sizeof why, "re-simulated with %s, the held-out chi-square does not fall (%.0f before, %.0f after)", name,
                  g.chi2_before, g.chi2_after);
  } else {
    std::snprintf(why, sizeof why,
                  "re-simulated with %s, the held-out chi-square falls by %.0f %% of the gap beyond the noise (%.0f before, %.0f "
                  "after, noise drives %.0f): most of this drive's gap is something no candidate holds",
                  name, 100.0 * gap_shrink(g), g.chi2_before, g.chi2_after, g.null_chi2_mean);
  }
  g.withheld = why;
  unname(g, lib, alone_shift);
  g.after = g.calibrated;
  held_out(g, (real - g.calibrated).cwiseQuotient(lib.sigma), (real - g.after).cwiseQuotient(lib.sigma));
}

}  // namespace

bool gap_visible(const GapResult& g) { return g.chi2_before - g.null_chi2_mean > 4.0 * std::max(g.null_chi2_sd, 10.0); }

double gap_shrink(const GapResult& g) {
  if (!gap_visible(g)) return 0.0;
  return 1.0 - std::max(0.0, g.chi2_after - g.null_chi2_mean) / (g.chi2_before - g.null_chi2_mean);
}

namespace {

// The held-out half's residual as the model was, with the nominal truck, and with the chosen
// effects, per channel and overall.
void held_out(GapResult& g, const Eigen::VectorXd& calibrated_z, const Eigen::VectorXd& after_z) {
  const Problem& p = g.problem;
  g.channels.clear();
  g.chi2_raw = g.chi2_before = g.chi2_after = 0;
  g.held_out = 0;
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < p.keys.size(); ++i) {
    const auto zi = static_cast<Eigen::Index>(i);
    const double raw = p.z(zi), before = calibrated_z(zi), after = after_z(zi);
    if (p.keys[i].half != 1 || !std::isfinite(raw) || !std::isfinite(before) || !std::isfinite(after)) continue;
    const std::string& ch = p.keys[i].channel;
    if (!index.count(ch)) {
      index[ch] = g.channels.size();
      g.channels.push_back({ch, 0, 0, 0, 0});
    }
    ChannelResidual& c = g.channels[index[ch]];
    c.features += 1;
    c.raw += raw * raw;
    c.before += before * before;
    c.after += after * after;
    g.chi2_raw += raw * raw;
    g.chi2_before += before * before;
    g.chi2_after += after * after;
    g.held_out += 1;
  }
  for (auto& c : g.channels) {
    for (double* v : {&c.raw, &c.before, &c.after}) *v = std::sqrt(*v / static_cast<double>(c.features));
  }
  if (g.held_out > 0) {
    g.residual_raw = std::sqrt(g.chi2_raw / static_cast<double>(g.held_out));
    g.residual_before = std::sqrt(g.chi2_before / static_cast<double>(g.held_out));
    g.residual_after = std::sqrt(g.chi2_after / static_cast<double>(g.held_out));
  }
}

}  // namespace
}  // namespace roadload::gap
