#include "roadload/gap/tables.hpp"

#include <algorithm>
#include <cmath>

#include "roadload/gap/nominal.hpp"
#include "roadload/gap/parallel.hpp"
#include "roadload/sim/simulation.hpp"

namespace roadload::gap {
namespace {

class NullSink final : public sim::SampleSink {
 public:
  void frame(const CanFrame&) override {}
  void accel(const AccelSample&) override {}
  void gnss(const GnssFix&) override {}
  void weather(const WeatherSample&) override {}
};

// Mean damper power over the cells the whole truck crossed, by surface: {bituminous, concrete}.
std::pair<double, double> damper_power(const sim::Scenario& s, const j1939::Database& db) {
  sim::Simulation simulation(s, 1, db);
  sim::TruthRecorder truth(simulation.route(), simulation.plant().truck());
  NullSink sink;
  simulation.run(sink, &truth);
  double sum[2] = {0, 0}, n[2] = {0, 0};
  for (const auto& c : truth.cells()) {
    if (!c.complete) continue;
    const int k = c.surface == "concrete" ? 1 : 0;
    sum[k] += c.damper_power_w;
    n[k] += 1;
  }
  return {n[0] > 0 ? sum[0] / n[0] : NAN, n[1] > 0 ? sum[1] / n[1] : NAN};
}

struct Job {
  sim::Scenario scenario;
  std::pair<double, double> power{};
};

void run_all(std::vector<Job>& jobs, const j1939::Database& db, unsigned threads) {
  parallel_for(jobs.size(), threads, [&](std::size_t i) { jobs[i].power = damper_power(jobs[i].scenario, db); });
}

// The candidates that change how a truck bounces, and the magnitudes tried on the Mainline.
constexpr sim::Effect kVertical[] = {sim::Effect::joint_faulting, sim::Effect::slab_curl, sim::Effect::suspension_friction,
                                     sim::Effect::tire_pressure};
constexpr int kSteps = 4;
// A nominal parameter moving the power by less than this share at one sigma is left at its value.
constexpr double kActs = 0.01;

// A candidate's Mainline ratio at each simulated magnitude, and the magnitude giving the report's
// ratio: linear interpolation between simulated ones, else the closest simulated.
TableCandidate bracket(sim::Effect e, const std::vector<Job>& first, std::size_t offset) {
  TableCandidate cand{e, {}, false, 0, 0, 0};
  const sim::EffectInfo& info = sim::effect_info(e);
  for (int k = 0; k < kSteps; ++k) {
    const auto& p = first[offset + static_cast<std::size_t>(k)].power;
    cand.mainline_ratio.emplace_back(info.min + (info.max - info.min) * k / (kSteps - 1), p.second / p.first);
  }
  double best = INFINITY;
  for (std::size_t k = 0; k < cand.mainline_ratio.size(); ++k) {
    const auto [m, r] = cand.mainline_ratio[k];
    if (std::abs(r - kReportMainlineRatio) < best && !cand.reached) {
      best = std::abs(r - kReportMainlineRatio);
      cand.magnitude = m;
    }
    if (k == 0) continue;
    const auto [m0, r0] = cand.mainline_ratio[k - 1];
    if (!cand.reached && (r0 - kReportMainlineRatio) * (r - kReportMainlineRatio) <= 0 && r != r0) {
      cand.reached = true;
      cand.magnitude = m0 + (kReportMainlineRatio - r0) / (r - r0) * (m - m0);
    }
  }
  return cand;
}

// The ratio grows about with the square of a joint's height: the interpolated magnitudes refined by
// two rounds of regula falsi on the Mainline alone.
void refine(std::vector<TableCandidate>& candidates, const sim::Scenario& mainline, const j1939::Database& db, unsigned jobs,
            const std::function<void(const std::string&)>& say) {
  for (int round = 0; round < 2; ++round) {
    std::vector<Job> runs;
    std::vector<std::size_t> which;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (!candidates[c].reached) continue;
      Job j{mainline, {}};
      j.scenario.effects.set(candidates[c].effect, candidates[c].magnitude);
      runs.push_back(std::move(j));
      which.push_back(c);
    }
    say("tables: refining " + std::to_string(runs.size()) + " magnitude(s) on the Mainline");
    run_all(runs, db, jobs);
    for (std::size_t i = 0; i < which.size(); ++i) {
      TableCandidate& cand = candidates[which[i]];
      auto& pts = cand.mainline_ratio;
      pts.emplace_back(cand.magnitude, runs[i].power.second / runs[i].power.first);
      std::sort(pts.begin(), pts.end());
      for (std::size_t k = 1; k < pts.size(); ++k) {
        const auto [m0, r0] = pts[k - 1];
        const auto [m1, r1] = pts[k];
        if ((r0 - kReportMainlineRatio) * (r1 - kReportMainlineRatio) <= 0 && r1 != r0) {
          cand.magnitude = m0 + (kReportMainlineRatio - r0) / (r1 - r0) * (m1 - m0);
          break;
        }
      }
    }
  }
}

// Each candidate at its fitted magnitude on every road: the highways' ratio it predicts, held out
// from the fit, chooses it.
void judge(TablesResult& t, const sim::Scenario (&roads)[3], const j1939::Database& db, unsigned jobs,
           const std::function<void(const std::string&)>& say) {
  std::vector<Job> second;
  for (const auto& cand : t.candidates) {
    for (int road = 0; road < 3; ++road) {
      Job j{roads[road], {}};
      j.scenario.effects.set(cand.effect, cand.magnitude);
      second.push_back(std::move(j));
    }
  }
  say("tables: " + std::to_string(second.size()) + " simulations (each candidate at its fitted magnitude on every road)");
  run_all(second, db, jobs);
  double best_error = INFINITY;
  for (std::size_t c = 0; c < t.candidates.size(); ++c) {
    TableCandidate& cand = t.candidates[c];
    const double h10 = second[c * 3 + 1].power.second, h66 = second[c * 3 + 2].power.first;
    cand.highway_ratio = h10 / h66;
    cand.holdout_error = std::abs(cand.highway_ratio - kReportHighwayRatio) / kReportHighwayRatio;
    if (cand.reached && cand.holdout_error < best_error) {
      best_error = cand.holdout_error;
      t.chosen = static_cast<int>(c);
    }
  }
  if (t.chosen >= 0) {
    const auto c = static_cast<std::size_t>(t.chosen);
    t.rows[0].after_w = second[c * 3].power.first;
    t.rows[1].after_w = second[c * 3].power.second;
    t.rows[2].after_w = second[c * 3 + 2].power.first;
    t.rows[3].after_w = second[c * 3 + 1].power.second;
  }
}

// The choice on one truck: the baseline on every road, each candidate bracketed and refined on the
// Mainline, then judged on the highways.
TablesResult choose(const sim::Scenario (&roads)[3], const j1939::Database& db, unsigned jobs,
                    const std::function<void(const std::string&)>& say) {
  std::vector<Job> first;
  for (const auto& r : roads) first.push_back({r, {}});
  for (sim::Effect e : kVertical) {
    const sim::EffectInfo& info = sim::effect_info(e);
    for (int k = 0; k < kSteps; ++k) {
      Job j{roads[0], {}};
      j.scenario.effects.set(e, info.min + (info.max - info.min) * k / (kSteps - 1));
      first.push_back(std::move(j));
    }
  }
  say("tables: " + std::to_string(first.size()) + " simulations (IRI only, then each candidate on the Mainline)");
  run_all(first, db, jobs);

  TablesResult t;
  const auto [ml_bit, ml_con] = first[0].power;
  const double th10 = first[1].power.second, th66 = first[2].power.first;
  t.rows = {{"Mainline bituminous (Table 6.5)", 442, ml_bit, ml_bit},
            {"Mainline concrete (Table 6.5)", 652, ml_con, ml_con},
            {"TH 66 bituminous (Table 6.6)", 6486, th66, th66},
            {"TH 10 concrete (Table 6.6)", 9353, th10, th10}};
  for (std::size_t c = 0; c < std::size(kVertical); ++c) t.candidates.push_back(bracket(kVertical[c], first, 3 + c * kSteps));
  refine(t.candidates, roads[0], db, jobs, say);
  judge(t, roads, db, jobs, say);
  return t;
}

// How much each nominal parameter moves the Mainline's suspension power at one sigma, and, for
// those that move it, the choice redone at both ends of the parameter's 90 % interval: the four
// powers cannot fit the truck (each road's level is the report's Eq. 2.7 against the simulator's
// damper dissipation, a scale the ratios take out), so its prior carries through to the answer.
void nominal_check(TablesResult& t, const sim::Scenario (&roads)[3], const j1939::Database& db, unsigned jobs,
                   const std::function<void(const std::string&)>& say) {
  const std::vector<NominalPrior> priors = nominal_priors(roads[0]);
  std::vector<Job> moved;
  for (const NominalPrior& p : priors) {
    Job j{roads[0], {}};
    set_nominal(j.scenario, p.id, p.value + p.sigma);
    moved.push_back(std::move(j));
  }
  say("tables: " + std::to_string(moved.size()) + " simulations (each nominal parameter one sigma off, on the Mainline)");
  run_all(moved, db, jobs);
  for (std::size_t i = 0; i < priors.size(); ++i) {
    TablesNominal n{
        std::string(nominal_name(priors[i].id)), std::string(nominal_unit(priors[i].id)), priors[i].value, priors[i].sigma, 0, {}};
    const double bit = moved[i].power.first / t.rows[0].before_w - 1.0, con = moved[i].power.second / t.rows[1].before_w - 1.0;
    n.power_per_sigma = std::abs(bit) > std::abs(con) ? bit : con;
    if (std::abs(n.power_per_sigma) >= kActs) {
      for (const double k : {-1.645, 1.645}) {
        sim::Scenario at[3] = {roads[0], roads[1], roads[2]};
        for (auto& r : at) set_nominal(r, priors[i].id, priors[i].value + k * priors[i].sigma);
        const TablesResult again = choose(at, db, jobs, say);
        TablesNominal::End end{priors[i].value + k * priors[i].sigma, std::nullopt, 0, 0};
        if (again.chosen >= 0) {
          const TableCandidate& c = again.candidates[static_cast<std::size_t>(again.chosen)];
          end = {end.value, c.effect, c.magnitude, c.highway_ratio};
        }
        n.ends.push_back(end);
      }
    }
    t.nominal.push_back(std::move(n));
  }
}

}  // namespace

Parsed<TablesResult> compare_tables(const std::string& data_dir, const j1939::Database& db, unsigned jobs,
                                    const std::function<void(const std::string&)>& progress) {
  sim::Scenario roads[3];
  const char* names[3] = {"mnroad-mainline-30mph", "th10-55mph", "th66-55mph"};
  for (int i = 0; i < 3; ++i) {
    auto s = sim::load_scenario(names[i], data_dir);
    if (!s) return s.error();
    roads[i] = std::move(s.value());
    // The baseline knows each pavement by its IRI and nothing else.
    roads[i].effects = sim::EffectSet();
  }
  const std::function<void(const std::string&)> say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  TablesResult t = choose(roads, db, jobs, say);
  nominal_check(t, roads, db, jobs, say);
  return t;
}

}  // namespace roadload::gap
