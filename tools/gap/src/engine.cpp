#include "roadload/gap/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace roadload::gap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kBaselineSeed = 1;
constexpr std::uint64_t kNoiseSeed0 = 1000;

Eigen::VectorXd values(const std::vector<RecordedRun>& runs) {
  std::size_t n = 0;
  for (const auto& r : runs) n += r.features.features.size();
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  Eigen::Index i = 0;
  for (const auto& r : runs) {
    for (const auto& f : r.features.features) v(i++) = f.value;
  }
  return v;
}

// The recordings' features in the library's order. A recording may carry other sensors than the
// model's truck: what the model has and the recording lacks is missing (NaN), the rest is ignored.
Eigen::VectorXd aligned(const std::vector<RealRun>& runs, const ModelLibrary& lib) {
  std::map<std::tuple<std::string, std::string, std::string, std::uint8_t>, double> real;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (const Feature& f : runs[r].recorded.features.features) real[{lib.labels[r], f.channel, f.where, f.half}] = f.value;
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(lib.keys.size()));
  for (std::size_t i = 0; i < lib.keys.size(); ++i) {
    const FeatureKey& k = lib.keys[i];
    const auto it = real.find({k.run, k.channel, k.where, lib.feature_half[i]});
    v(static_cast<Eigen::Index>(i)) = it == real.end() ? kNaN : it->second;
  }
  return v;
}

}  // namespace

std::vector<UnmatchedChannel> unmatched_channels(const std::vector<RealRun>& runs, const ModelLibrary& lib) {
  std::vector<UnmatchedChannel> out;
  for (std::size_t r = 0; r < runs.size() && r < lib.labels.size(); ++r) {
    std::set<std::string> real, model;
    for (const Feature& f : runs[r].recorded.features.features) real.insert(f.channel);
    for (const FeatureKey& k : lib.keys) {
      if (k.run == lib.labels[r]) model.insert(k.channel);
    }
    for (const std::string& c : real) {
      if (!model.contains(c)) out.push_back({lib.labels[r], c, true});
    }
    for (const std::string& c : model) {
      if (!real.contains(c)) out.push_back({lib.labels[r], c, false});
    }
  }
  return out;
}

namespace {

// Magnitudes the library simulates and a fit may take: the catalog's realistic range, widened by
// a quarter, reaching zero for an effect that cannot be negative.
struct Span {
  double lo, hi, m1, m2;
};
Span span_of(const sim::EffectInfo& info, double base) {
  const double width = info.max - info.min;
  if (info.min < 0) return {info.min - 0.25 * width, info.max + 0.25 * width, info.max, info.min};
  return {0.0, info.max + 0.25 * width, info.max, 0.5 * (base + info.max) > 0 ? 0.5 * (base + info.max) : 0.5 * info.max};
}

// The smallest gap worth explaining per channel: below it a feature is as good as its sensor
// (CCVS1 speed 1/256 km/h, FD1 fan 0.125 rpm) or the model is as good as anyone needs
// (1 N m of engine torque, 0.05 L/h, 2 cm of height, 0.1 dB of vibration).
double noise_floor(const std::string& channel) {
  if (channel == "speed_mps") return 0.005;
  if (channel == "speed_sd_mps") return 0.005;
  if (channel == "fan_rpm") return 2.0;
  if (channel == "torque_nm" || channel == "torque_sd_nm") return 1.0;
  if (channel == "fuel_lph") return 0.05;
  if (channel == "gnss_alt_m") return 0.02;
  return 0.1;  // psd_db
}

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
void set_noise_floor(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals);
}  // namespace

ModelLibrary build_library(const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options) {
  ModelLibrary lib;
  lib.scenarios = resimulations(runs);
  for (const RealRun& r : runs) {
    lib.labels.push_back(r.label);
    lib.layouts.push_back(layout_for(r.model.route));
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
  // Noise drives: the model itself driven with seeds of its own and its own wandering wind, each
  // then re-simulated from its recording exactly as a real drive is, so the floor holds every
  // difference the pipeline makes when nothing is missing from the model.
  std::vector<SimTask> noise_drives;
  for (std::size_t k = 0; k < options.noise_runs; ++k) {
    for (std::size_t r = 0; r < n_runs; ++r) {
      sim::Scenario s = lib.scenarios[r];
      s.weather.wind_trace.clear();
      noise_drives.push_back({std::move(s), kNoiseSeed0 + k, &lib.layouts[r]});
    }
  }
  say(options, "library: " + std::to_string(noise_drives.size()) + " noise drives");
  const std::vector<RecordedRun> noise = simulate_all(noise_drives, db, options.jobs, options.progress);
  for (std::size_t k = 0; k < options.noise_runs; ++k) {
    for (std::size_t r = 0; r < n_runs; ++r) {
      const RecordedRun& drive = noise[k * n_runs + r];
      tasks.push_back({resimulation(runs[r].model, drive.features.conditions, drive.meta), kBaselineSeed, &lib.layouts[r]});
    }
  }
  for (const sim::EffectInfo& info : sim::effect_catalog()) {
    const double base = lib.scenarios.front().effects.magnitude(info.id);
    const Span sp = span_of(info, base);
    lib.responses.push_back({info.id, base, sp.m1, sp.m2, {}, {}});
    add_all([&](sim::Scenario& s) { add_candidate(s, info.id, sp.m1); }, kBaselineSeed);
    add_all([&](sim::Scenario& s) { add_candidate(s, info.id, sp.m2); }, kBaselineSeed);
  }
  say(options,
      "library: " + std::to_string(tasks.size()) + " simulations (baseline, the noise drives' re-simulations, 2 per effect)");
  const std::vector<RecordedRun> sims = simulate_all(tasks, db, options.jobs, options.progress);
  auto group = [&](std::size_t g) {
    return std::vector<RecordedRun>(sims.begin() + static_cast<std::ptrdiff_t>(g * n_runs),
                                    sims.begin() + static_cast<std::ptrdiff_t>((g + 1) * n_runs));
  };
  const std::vector<RecordedRun> base = group(0);
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
    const std::vector<RecordedRun> drive(noise.begin() + static_cast<std::ptrdiff_t>(k * n_runs),
                                         noise.begin() + static_cast<std::ptrdiff_t>((k + 1) * n_runs));
    residuals.push_back(values(drive) - values(group(1 + k)));
  }
  set_noise_floor(lib, residuals);
  for (std::size_t e = 0; e < lib.responses.size(); ++e) {
    lib.responses[e].f1 = values(group(1 + options.noise_runs + 2 * e));
    lib.responses[e].f2 = values(group(2 + options.noise_runs + 2 * e));
  }
  return lib;
}

namespace {

// Noise floor: each feature's scatter over the noise drives' residuals, pooled with its channel's
// so eight seeds do not make a few features look too quiet; then the held-out chi-square those
// drives reach against it, the bench's measure of an effect's visibility.
void set_noise_floor(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals) {
  const auto n = lib.baseline.size();
  Eigen::VectorXd own = Eigen::VectorXd::Zero(n), count = Eigen::VectorXd::Zero(n);
  for (const Eigen::VectorXd& d : residuals) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::isfinite(d(i))) own(i) += d(i) * d(i), count(i) += 1;
    }
  }
  std::map<std::pair<std::string, std::string>, std::pair<double, double>> pooled;
  for (Eigen::Index i = 0; i < n; ++i) {
    auto& p = pooled[{lib.keys[static_cast<std::size_t>(i)].run, lib.keys[static_cast<std::size_t>(i)].channel}];
    p.first += own(i);
    p.second += count(i);
  }
  constexpr double kPrior = 4.0;
  lib.sigma.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& p = pooled[{lib.keys[static_cast<std::size_t>(i)].run, lib.keys[static_cast<std::size_t>(i)].channel}];
    const double channel_var = p.second > 0 ? p.first / p.second : kNaN;
    const double var = (own(i) + kPrior * channel_var) / (count(i) + kPrior);
    const double floor = noise_floor(lib.keys[static_cast<std::size_t>(i)].channel);
    lib.sigma(i) = count(i) >= 2 && std::isfinite(var) ? std::max(std::sqrt(var), floor) : kNaN;
  }
  std::vector<double> null_chi2;
  for (const Eigen::VectorXd& d : residuals) {
    const Eigen::VectorXd z = d.cwiseQuotient(lib.sigma);
    double chi2 = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (lib.keys[static_cast<std::size_t>(i)].half == 1 && std::isfinite(z(i))) chi2 += z(i) * z(i);
    }
    null_chi2.push_back(chi2);
  }
  for (double c : null_chi2) lib.null_chi2_mean += c / static_cast<double>(null_chi2.size());
  for (double c : null_chi2) lib.null_chi2_sd += (c - lib.null_chi2_mean) * (c - lib.null_chi2_mean);
  lib.null_chi2_sd = std::sqrt(lib.null_chi2_sd / std::max<double>(1.0, static_cast<double>(null_chi2.size()) - 1.0));
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
    if (std::abs(a.weather.wind_speed_mps - b.weather.wind_speed_mps) > 1.5) return false;
    if (std::abs(std::remainder(a.weather.wind_from_deg - b.weather.wind_from_deg, 360.0)) > 30.0) return false;
  }
  return true;
}

namespace {
std::vector<Candidate> candidates(const ModelLibrary& lib, const Eigen::VectorXd& model, const Eigen::VectorXd& yaw);
Eigen::VectorXd with_chosen(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Fit& f,
                            const j1939::Database& db, const GapOptions& options);
void held_out(GapResult& g, const Eigen::VectorXd& after_z);
}  // namespace

GapResult run_gap(const ModelLibrary& lib, const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options) {
  const std::vector<sim::Scenario> resims = resimulations(runs);
  std::vector<SimTask> tasks;
  for (std::size_t r = 0; r < runs.size(); ++r) tasks.push_back({resims[r], kBaselineSeed, &lib.layouts[r]});
  say(options, "re-simulating " + std::to_string(runs.size()) + " run(s)");
  const Eigen::VectorXd model = values(simulate_all(tasks, db, options.jobs));
  const Eigen::VectorXd real = aligned(runs, lib);

  GapResult g;
  Problem& p = g.problem;
  p.keys = lib.keys;
  p.z = (real - model).cwiseQuotient(lib.sigma);
  // Drag that grows with the yaw angle follows the crosswind the truck met, cell by cell: its
  // response is simulated on this drive's own wind rather than taken from the library's. It is
  // linear in its magnitude, so one simulation gives it (at the library's first magnitude).
  const auto yaw_response = std::find_if(lib.responses.begin(), lib.responses.end(),
                                         [](const auto& r) { return r.effect == sim::Effect::yaw_drag; });
  std::vector<SimTask> own;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    sim::Scenario s = resims[r];
    add_candidate(s, sim::Effect::yaw_drag, yaw_response->m1);
    own.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
  }
  const Eigen::VectorXd yaw = values(simulate_all(own, db, options.jobs));
  p.candidates = candidates(lib, model, yaw);
  say(options, "fitting " + std::to_string(p.candidates.size()) + " candidate effects and their pairs");
  g.diagnosis = diagnose(p, options.rule);
  for (const RealRun& run : runs) {
    if (run.caveat.empty()) continue;
    g.withheld += (g.withheld.empty() ? "" : "; ") + run.label + ": " + run.caveat;
  }
  if (!g.withheld.empty()) g.diagnosis.chosen.reset();

  g.null_chi2_mean = lib.null_chi2_mean;
  g.null_chi2_sd = lib.null_chi2_sd;
  g.real = real;
  g.model = model;
  g.sigma = lib.sigma;
  g.after = model;
  Eigen::VectorXd after_z = p.z;
  if (g.diagnosis.chosen) {
    say(options, "re-simulating with the chosen effect added (fitted on half 0)");
    g.after = with_chosen(lib, resims, *g.diagnosis.chosen, db, options);
    after_z = (real - g.after).cwiseQuotient(lib.sigma);
  }
  held_out(g, after_z);
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

// The drives re-simulated with the chosen effects at their magnitudes fitted on half 0.
Eigen::VectorXd with_chosen(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims, const Fit& f,
                            const j1939::Database& db, const GapOptions& options) {
  std::vector<SimTask> after;
  for (std::size_t r = 0; r < resims.size(); ++r) {
    sim::Scenario s = resims[r];
    for (std::size_t i = 0; i < f.effects.size(); ++i) {
      const auto& resp = lib.responses[f.effects[i]];
      add_candidate(s, resp.effect, f.magnitude_half0[i]);
    }
    after.push_back({std::move(s), kBaselineSeed, &lib.layouts[r]});
  }
  return values(simulate_all(after, db, options.jobs));
}

// The held-out half's residual before and after the chosen effects, per channel and overall.
void held_out(GapResult& g, const Eigen::VectorXd& after_z) {
  const Problem& p = g.problem;
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < p.keys.size(); ++i) {
    const auto zi = static_cast<Eigen::Index>(i);
    if (p.keys[i].half != 1 || !std::isfinite(p.z(zi)) || !std::isfinite(after_z(zi))) continue;
    const std::string& ch = p.keys[i].channel;
    if (!index.count(ch)) {
      index[ch] = g.channels.size();
      g.channels.push_back({ch, 0, 0, 0});
    }
    ChannelResidual& c = g.channels[index[ch]];
    c.features += 1;
    c.before += p.z(zi) * p.z(zi);
    c.after += after_z(zi) * after_z(zi);
    g.chi2_before += p.z(zi) * p.z(zi);
    g.chi2_after += after_z(zi) * after_z(zi);
    g.held_out += 1;
  }
  for (auto& c : g.channels) {
    c.before = std::sqrt(c.before / static_cast<double>(c.features));
    c.after = std::sqrt(c.after / static_cast<double>(c.features));
  }
  if (g.held_out > 0) {
    g.residual_before = std::sqrt(g.chi2_before / static_cast<double>(g.held_out));
    g.residual_after = std::sqrt(g.chi2_after / static_cast<double>(g.held_out));
  }
}

}  // namespace
}  // namespace roadload::gap
