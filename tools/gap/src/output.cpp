#include "roadload/gap/output.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "roadload/gap/unseen.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/results/json.hpp"

namespace roadload::gap {
namespace {

std::string effect_list(const GapResult& g) {
  if (!g.diagnosis.chosen) return "none";
  std::string s;
  const Fit& f = *g.diagnosis.chosen;
  for (std::size_t i = 0; i < f.effects.size(); ++i) s += (i ? " + " : "") + g.problem.candidates[f.effects[i]].name;
  return s;
}

// The first rows of the answer: how the model's truck differs from this one.
void print_nominal(std::FILE* out, const GapResult& g) {
  const NominalFit& n = g.diagnosis.nominal;
  if (n.value.empty()) {
    std::fprintf(out, "\nnominal truck: held as modelled (the vehicle file states no spreads)\n");
    return;
  }
  std::fprintf(out, "\nthe model's truck against this one (fitted on half 0%s; 90 %% interval; prior sigma):\n",
               g.diagnosis.chosen ? " beside the named effect" : "");
  for (std::size_t j = 0; j < n.value.size(); ++j) {
    const NominalColumn& c = g.problem.nominal[j];
    const bool moved = std::abs(n.shift_sigma[j]) >= 1.0 && (c.value < n.lo[j] || c.value > n.hi[j]);
    std::fprintf(out, "  %-22s %10.4g -> %-10.4g [%.4g, %.4g] %s  (prior %.3g, %+.1f sigma)%s\n", c.name.c_str(), c.value, n.value[j],
                 n.lo[j], n.hi[j], c.unit.c_str(), c.sigma, n.shift_sigma[j], moved ? "  <- not the model's" : "");
  }
  std::fprintf(out, "  held-out residual (RMS z, re-simulated): %.2f as modelled -> %.2f with this truck\n", g.residual_raw,
               g.residual_before);
}

void nominal_json(std::ostringstream& j, const GapResult& g) {
  const NominalFit& n = g.diagnosis.nominal;
  j << "  \"nominal\": [";
  for (std::size_t i = 0; i < n.value.size(); ++i) {
    const NominalColumn& c = g.problem.nominal[i];
    j << (i ? "," : "") << "\n    {\"name\": " << results::json_quote(c.name) << ", \"unit\": " << results::json_quote(c.unit)
      << ", \"model\": " << json_number(c.value) << ", \"prior_sigma\": " << json_number(c.sigma)
      << ", \"fitted\": " << json_number(n.value[i]) << ", \"lo\": " << json_number(n.lo[i]) << ", \"hi\": " << json_number(n.hi[i])
      << ", \"shift_sigma\": " << json_number(n.shift_sigma[i]) << "}";
  }
  j << "\n  ],\n  \"residual_raw\": " << json_number(g.residual_raw) << ",\n";
}

}  // namespace

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o.precision(8);
  o << v;
  return o.str();
}

namespace {

// One line per reason, the effects it keeps out named before it.
void print_not_fitted(std::FILE* out) {
  std::vector<std::pair<const char*, std::string>> reasons;
  for (const auto& e : sim::effect_catalog()) {
    const char* why = unseen_by_features(e.id);
    if (why == nullptr) continue;
    auto it = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return std::string_view(r.first) == why; });
    if (it == reasons.end()) it = reasons.insert(reasons.end(), {why, std::string()});
    it->second += (it->second.empty() ? "" : ", ") + std::string(e.name);
  }
  for (const auto& [why, names] : reasons) std::fprintf(out, "  not fitted: %s: %s\n", names.c_str(), why);
}

}  // namespace

void print_result(std::FILE* out, const GapResult& g, const std::vector<std::string>& run_lines) {
  const Diagnosis& d = g.diagnosis;
  for (const auto& line : run_lines) std::fprintf(out, "%s\n", line.c_str());
  print_nominal(out, g);
  std::fprintf(out, "\nresidual: %zu features, chi-square %.0f against %zu expected from the noise floor\n", d.features, d.chi2,
               d.features);
  std::fprintf(out, "\nwhere the gap lies (sigma = excess chi-square / sqrt(2 n)):\n");
  std::fprintf(out, "  %-22s %-24s %5s %8s %7s  %s\n", "run", "channel", "n", "excess", "sigma", "worst place (z)");
  if (d.where.empty()) std::fprintf(out, "  nowhere beyond the noise floor\n");
  for (const WhereItem& w : d.where) {
    std::fprintf(out, "  %-22s %-24s %5zu %8.1f %7.1f  %s (%+.1f)\n", w.run.c_str(), w.channel.c_str(), w.features, w.excess,
                 w.significance, w.worst_where.c_str(), w.worst_z);
  }
  std::fprintf(out,
               "\ncandidates (held-out chi-square removed, both folds, minus %g per magnitude, times the plausibility of\n"
               "the magnitude and of the truck beside it; in brackets the most it removed from a noise drive):\n",
               2.0);
  const std::size_t shown = std::min<std::size_t>(6, d.singles.size());
  for (std::size_t i = 0; i < shown; ++i) {
    const Fit& f = d.singles[i];
    const Candidate& c = g.problem.candidates[f.effects[0]];
    char truck[96];
    std::snprintf(truck, sizeof truck, "  (beside a truck %.1f sigma from the model's%s)", f.truck_sigma,
                  f.scored_truck_kept ? "; scored beside the truck fitted alone" : "");
    const std::string note = !c.stood_for_by.empty()       ? "  (the nominal " + c.stood_for_by + " stands for it)"
                             : f.plausibility < 0.99       ? "  (outside its realistic range)"
                             : f.truck_plausibility < 0.99 ? std::string(truck)
                                                           : "";
    std::fprintf(out, "  %-22s gain %8.1f (%5.0f)   %s = %.4g %s [%.4g, %.4g]%s\n", c.name.c_str(), f.gain, c.null_gain,
                 c.name.c_str(), f.magnitude[0], c.unit.c_str(), f.lo[0], f.hi[0], note.c_str());
  }
  if (d.best_pair) {
    const Fit& f = *d.best_pair;
    std::fprintf(out, "  best pair: %s + %s, gain %.1f\n", g.problem.candidates[f.effects[0]].name.c_str(),
                 g.problem.candidates[f.effects[1]].name.c_str(), f.gain);
  }
  print_not_fitted(out);
  if (!g.withheld.empty()) {
    std::fprintf(out, "\neffect: none named: %s\n", g.withheld.c_str());
  } else if (!d.chosen) {
    std::fprintf(out, "\neffect: none: no candidate explains the gap significantly\n");
  } else {
    const Fit& f = *d.chosen;
    std::fprintf(out, "\neffect: %s\n", effect_list(g).c_str());
    for (std::size_t i = 0; i < f.effects.size(); ++i) {
      const Candidate& c = g.problem.candidates[f.effects[i]];
      std::fprintf(out, "  %s = %.4g %s, 90 %% interval [%.4g, %.4g] (model had %.4g)\n", c.name.c_str(), f.magnitude[i],
                   c.unit.c_str(), f.lo[i], f.hi[i], c.base);
    }
    if (!d.rivals.empty()) {
      std::fprintf(out, "  not told apart from (gain within what noise alone gives of %s's):",
                   g.problem.candidates[f.effects[0]].name.c_str());
      for (std::size_t i = 0; i < d.rivals.size(); ++i) {
        std::fprintf(out, "%s %s %.1f", i ? "," : "", g.problem.candidates[d.rivals[i].effects[0]].name.c_str(), d.rivals[i].gain);
      }
      std::fprintf(out, "\n");
    }
  }
  std::fprintf(out,
               "\nheld-out residual (RMS z on half 1, re-simulated: as modelled, with the truck fitted on half 0, and with\n"
               "the effect fitted there as well):\n");
  std::fprintf(out, "  %-24s %5s %8s %8s %8s\n", "channel", "n", "modelled", "truck", "after");
  for (const ChannelResidual& c : g.channels) {
    std::fprintf(out, "  %-24s %5zu %8.2f %8.2f %8.2f\n", c.channel.c_str(), c.features, c.raw, c.before, c.after);
  }
  std::fprintf(out, "  %-24s %5zu %8.2f %8.2f %8.2f\n", "overall", g.held_out, g.residual_raw, g.residual_before, g.residual_after);
  if (!g.unmatched.empty()) std::fprintf(out, "\nnot compared (sensors matched by mounting position):\n");
  for (const UnmatchedChannel& u : g.unmatched) {
    std::fprintf(out, "  %-22s %-32s %s\n", u.run.c_str(), u.channel.c_str(),
                 u.recording_only ? "the model's truck has no sensor there" : "the recording has no sensor there");
  }
}

std::string result_json(const GapResult& g, const std::vector<std::string>& run_lines) {
  const Diagnosis& d = g.diagnosis;
  std::ostringstream j;
  j << "{\n";
  if (d.chosen) {
    const Fit& f = *d.chosen;
    const Candidate& c = g.problem.candidates[f.effects[0]];
    j << "  \"effect\": " << results::json_quote(c.name) << ",\n  \"magnitude\": " << json_number(f.magnitude[0])
      << ",\n  \"unit\": " << results::json_quote(c.unit) << ",\n  \"interval\": [" << json_number(f.lo[0]) << ", "
      << json_number(f.hi[0]) << "],\n";
  } else {
    j << "  \"effect\": null,\n  \"magnitude\": null,\n  \"unit\": null,\n  \"interval\": null,\n";
  }
  nominal_json(j, g);
  j << "  \"effects\": [";
  if (d.chosen) {
    const Fit& f = *d.chosen;
    for (std::size_t i = 0; i < f.effects.size(); ++i) {
      const Candidate& c = g.problem.candidates[f.effects[i]];
      j << (i ? ", " : "") << "{\"name\": " << results::json_quote(c.name) << ", \"magnitude\": " << json_number(f.magnitude[i])
        << ", \"lo\": " << json_number(f.lo[i]) << ", \"hi\": " << json_number(f.hi[i])
        << ", \"fitted_on_half0\": " << json_number(f.magnitude_half0[i]) << ", \"unit\": " << results::json_quote(c.unit) << "}";
    }
  }
  j << "],\n  \"where\": [";
  for (std::size_t i = 0; i < d.where.size(); ++i) {
    const WhereItem& w = d.where[i];
    j << (i ? "," : "") << "\n    {\"run\": " << results::json_quote(w.run) << ", \"channel\": " << results::json_quote(w.channel)
      << ", \"features\": " << w.features << ", \"excess_chi2\": " << json_number(w.excess)
      << ", \"sigma\": " << json_number(w.significance) << ", \"worst\": " << results::json_quote(w.worst_where)
      << ", \"worst_z\": " << json_number(w.worst_z) << "}";
  }
  j << "\n  ],\n  \"residual_before\": " << json_number(g.residual_before)
    << ",\n  \"residual_after\": " << json_number(g.residual_after) << ",\n  \"held_out_features\": " << g.held_out
    << ",\n  \"channels\": [";
  for (std::size_t i = 0; i < g.channels.size(); ++i) {
    const ChannelResidual& c = g.channels[i];
    j << (i ? "," : "") << "\n    {\"channel\": " << results::json_quote(c.channel) << ", \"features\": " << c.features
      << ", \"raw\": " << json_number(c.raw) << ", \"before\": " << json_number(c.before) << ", \"after\": " << json_number(c.after)
      << "}";
  }
  j << "\n  ],\n  \"candidates\": [";
  for (std::size_t i = 0; i < d.singles.size(); ++i) {
    const Fit& f = d.singles[i];
    j << (i ? "," : "") << "\n    {\"name\": " << results::json_quote(g.problem.candidates[f.effects[0]].name)
      << ", \"gain\": " << json_number(f.gain) << ", \"noise_gain\": " << json_number(g.problem.candidates[f.effects[0]].null_gain)
      << ", \"magnitude\": " << json_number(f.magnitude[0]) << ", \"plausibility\": " << json_number(f.plausibility)
      << ", \"truck_sigma\": " << json_number(f.truck_sigma) << ", \"truck_plausibility\": " << json_number(f.truck_plausibility)
      << ", \"gain_truck_kept\": " << json_number(f.gain_truck_kept) << "}";
  }
  j << "\n  ],\n  \"rivals\": [";
  for (std::size_t i = 0; d.chosen && i < d.rivals.size(); ++i) {
    j << (i ? "," : "") << "\n    {\"name\": " << results::json_quote(g.problem.candidates[d.rivals[i].effects[0]].name)
      << ", \"gain\": " << json_number(d.rivals[i].gain) << "}";
  }
  j << "\n  ],\n  \"not_fitted\": [";
  bool first = true;
  for (const auto& e : sim::effect_catalog()) {
    const char* why = unseen_by_features(e.id);
    if (why == nullptr) continue;
    j << (first ? "" : ",") << "\n    {\"name\": " << results::json_quote(std::string(e.name))
      << ", \"why\": " << results::json_quote(why) << "}";
    first = false;
  }
  j << "\n  ],\n  \"withheld\": " << (g.withheld.empty() ? std::string("null") : results::json_quote(g.withheld));
  j << ",\n  \"unmatched\": [";
  for (std::size_t i = 0; i < g.unmatched.size(); ++i) {
    const UnmatchedChannel& u = g.unmatched[i];
    j << (i ? "," : "") << "\n    {\"run\": " << results::json_quote(u.run) << ", \"channel\": " << results::json_quote(u.channel)
      << ", \"only_in\": " << results::json_quote(u.recording_only ? "recording" : "model") << "}";
  }
  j << "\n  ],\n  \"runs\": [";
  for (std::size_t i = 0; i < run_lines.size(); ++i) j << (i ? ", " : "") << results::json_quote(run_lines[i]);
  j << "]\n}\n";
  return j.str();
}

std::string features_csv(const GapResult& g) {
  std::ostringstream o;
  o.precision(9);
  o << "run,channel,where,half,real,model,sigma,z,calibrated,after\n";
  auto cell = [&](double v) -> std::ostringstream& {
    if (std::isfinite(v)) o << v;
    return o;
  };
  for (std::size_t i = 0; i < g.problem.keys.size(); ++i) {
    const FeatureKey& k = g.problem.keys[i];
    const auto r = static_cast<Eigen::Index>(i);
    o << k.run << ',' << k.channel << ',' << k.where << ',' << static_cast<int>(k.half) << ',';
    cell(g.real(r)) << ',';
    cell(g.model(r)) << ',';
    cell(g.sigma(r)) << ',';
    cell(g.problem.z(r)) << ',';
    cell(g.calibrated(r)) << ',';
    cell(g.after(r)) << '\n';
  }
  return o.str();
}

std::optional<ParseError> write_text_file(const std::string& path, const std::string& text) {
  auto file = recording::OutputFile::create(path);
  if (!file) return file.error();
  file.value().write(text);
  return file.value().close();
}

}  // namespace roadload::gap
