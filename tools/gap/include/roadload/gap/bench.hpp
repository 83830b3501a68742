#pragma once
// The withheld-effect check: drives simulated with effects the diagnosis is not told, diagnosed
// blind from what their recordings would hold, scored against what was really on.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// One test day on one road (config/bench/test-days.toml): its runs as driven and as the
// diagnosis is told them.
struct BenchDay {
  std::string road;
  std::vector<std::string> labels;    // as a user would name the recording folders
  std::vector<sim::Scenario> drives;  // what happened, before the hidden effects and the truck
  std::vector<sim::Scenario> models;  // what the diagnosis is told (the runs' scenarios)
};
// The days of a test-days file, errors naming its file, line and field.
Parsed<std::vector<BenchDay>> load_bench_days(const std::string& path, const std::string& data_dir);
std::string default_bench_days(const std::string& data_dir);

struct BenchCase {
  std::size_t day = 0;                                  // which test day (road)
  std::vector<std::pair<sim::Effect, double>> effects;  // empty: a null run
  std::uint64_t seed = 0;
  // The truck driven: each nominal parameter's offset from the model's in its prior sigmas
  // (nominal.hpp); empty: the model's own truck.
  std::vector<double> truck;
};

// The effects the bench draws from by default, and why the others are left out (nullptr: in).
std::vector<sim::Effect> observable_effects();
const char* unobservable(sim::Effect e);

struct BenchPlan {
  std::size_t cases = 50;
  std::uint64_t seed = 1;
  double null_share = 0.2, pair_share = 0.15;
  std::vector<sim::Effect> effects;  // drawn from; observable_effects() when empty
  bool draw_trucks = true;           // else every case drives the model's own truck
};
// Each case's day is drawn uniformly among those whose roads can show its effect (joint and slab
// effects need jointed concrete). Magnitudes are uniform within each effect's realistic range,
// at least a quarter of the range away from the model's own value so that every effect case has a
// gap to find.
std::vector<BenchCase> draw_cases(const BenchPlan& plan, const std::vector<BenchDay>& days);

struct CaseOutcome {
  BenchCase truth;
  std::string road;
  GapResult result;
  bool named_right = false;  // null: nothing named; otherwise the first named effect was on
  bool rival_right = false;  // named wrongly, but a hidden effect is among the rivals it could not tell apart
  bool false_alarm = false;  // null run with an effect named
  bool visible = false;      // the effect raised the held-out chi-square 4 sd above the noise drives'
  double shrink = 0;         // share of that excess chi-square the named effect removed
  // Per nominal parameter (the diagnosis's order): the truck's true value and whether the
  // fitted 90 % interval holds it.
  std::vector<double> nominal_truth;
  std::vector<bool> nominal_covered;
};

CaseOutcome run_case(const BenchCase& c, const std::vector<BenchDay>& days, std::vector<ModelLibrary>& libraries,
                     const j1939::Database& db, const GapOptions& options);

std::string describe_effects(const std::vector<std::pair<sim::Effect, double>>& effects);

// The bench's score over its cases: top-1 (null runs count as right when nothing is named), the
// mean held-out shrink over cases whose effect is visible above the noise, the false-alarm rate on
// null runs, and the confusion of hidden against first named effects.
struct BenchScore {
  std::size_t cases = 0, right = 0, nulls = 0, alarms = 0, visible = 0;
  std::size_t wrong_names = 0, rival_right = 0;  // effects named wrongly, and of them CaseOutcome::rival_right
  double shrink_sum = 0;
  // Rows: the hidden effect, the first of a pair marked (+1); columns: the first named.
  std::map<std::string, std::map<std::string, int>> confusion;
  // Per nominal parameter: cases, intervals holding the truth, and the sum of squared errors in
  // the parameter's unit and of the prior's (what the fit started from).
  struct Recovery {
    std::string name, unit;
    std::size_t cases = 0, covered = 0;
    double error_ss = 0, prior_ss = 0;
  };
  std::vector<Recovery> nominal;
  std::map<std::string, std::pair<std::size_t, std::size_t>> by_road;  // right, cases

  void add(const CaseOutcome& o);
  double top1() const { return cases ? static_cast<double>(right) / static_cast<double>(cases) : 0.0; }
  double shrink() const { return visible ? shrink_sum / static_cast<double>(visible) : 0.0; }
  double false_alarm() const { return nulls ? static_cast<double>(alarms) / static_cast<double>(nulls) : 0.0; }
};

// "name=magnitude + ..." of what the case's diagnosis chose, "none" when nothing.
std::string named_effects(const CaseOutcome& o);

}  // namespace roadload::gap
