#pragma once
// The diagnosis end to end for one set of recorded runs: their re-simulations, the noise floor
// and candidate responses of the model (the library, reusable across drives in like
// conditions), the diagnosis, and the held-out check with the chosen effect added to the model.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "roadload/gap/diagnosis.hpp"
#include "roadload/gap/nominal.hpp"
#include "roadload/gap/resimulate.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/sim/effects.hpp"
#include "roadload/sim/scenario.hpp"

namespace roadload::gap {

// What the fit never sees: every other cell of every run, or every other run (the first, third,
// ... runs against the second, fourth, ...: a fit at one speed judged at another).
enum class Holdout { cells, runs };

struct GapOptions {
  std::size_t noise_runs = 8;  // seeds of the unchanged model that calibrate the noise floor
  Holdout holdout = Holdout::cells;
  unsigned jobs = 2;  // simulations at once
  DecisionRule rule;
  std::function<void(const std::string&)> progress;  // one line per step, for long runs
};

// A run as the diagnosis sees it: a label, the recording's metadata and features, and the model
// scenario the user named for it.
struct RealRun {
  std::string label;
  sim::Scenario model;
  RecordedRun recorded;
  // Why the model of this run cannot be trusted to name an effect (its road traced from the drive
  // itself); empty when it can. The diagnosis still says where the gap lies.
  std::string caveat;
};

struct ModelLibrary {
  std::vector<std::string> labels;
  std::vector<sim::Scenario> scenarios;  // the re-simulations the library was built on
  std::vector<RunLayout> layouts;
  std::vector<FeatureKey> keys;            // all runs' features, concatenated
  std::vector<std::uint8_t> feature_half;  // each feature's own half (keys' may be its run's: --holdout runs)
  Eigen::VectorXd baseline;                // the re-simulation's features
  Eigen::VectorXd sigma;                   // noise floor per feature
  struct Response {
    sim::Effect effect;
    double base, m1, m2;
    Eigen::VectorXd f1, f2;  // features with the effect at m1 and m2
  };
  std::vector<Response> responses;
  // Per response: the most its candidate removed from any noise drive (Candidate::null_gain).
  std::vector<double> null_gain;
  // The nominal parameters each run's model may move (the same for every run: one truck), and
  // the features' change with each at its value plus one sigma (columns).
  std::vector<std::vector<NominalPrior>> priors;
  Eigen::MatrixXd nominal_delta;
  // How far the nominal fit missed the noise drives' own trucks, RMS in prior sigmas per
  // parameter: the error the linear responses and the features' correlations add, which the
  // fit's curvature does not know. Intervals are widened by it.
  std::vector<double> nominal_miss;
  // The held-out half's chi-square of the noise drives: what a drive with nothing missing from
  // the model scores (mean and spread), against which a gap's excess is measured.
  double null_chi2_mean = 0, null_chi2_sd = 0;
  std::size_t null_chi2_count = 0;  // noise drives behind them
};

// Adds a candidate effect at a magnitude to a re-simulation. Most are the simulator's own effect;
// two are errors of what the recording says, so the model corrects its input instead: a recorded
// mass (1 + e) too high means the truck was lighter, a station reading d too warm means colder,
// denser air.
void add_candidate(sim::Scenario& s, sim::Effect e, double magnitude);

// The re-simulation of each run.
std::vector<sim::Scenario> resimulations(const std::vector<RealRun>& runs);

ModelLibrary build_library(const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options);
// Whether a library built for other drives may serve these: same routes and speeds, weather,
// mass and duration near enough that the responses and the noise floor carry over.
bool library_serves(const ModelLibrary& lib, const std::vector<sim::Scenario>& resims);

// A channel one side has and the other lacks, in one run: a recording's sensor at a position where
// the model's truck has none is left out of the comparison; a model sensor the recording lacks
// leaves its features missing. Either way the user is told, not left to wonder at a short list.
struct UnmatchedChannel {
  std::string run, channel;
  bool recording_only = false;  // else the model's only
};
std::vector<UnmatchedChannel> unmatched_channels(const std::vector<RealRun>& runs, const ModelLibrary& lib);

struct ChannelResidual {
  std::string channel;
  std::size_t features = 0;
  double raw = 0, before = 0, after = 0;  // RMS of z on held-out features: as GapResult's residuals
};

struct GapResult {
  Problem problem;
  // Per feature of problem.keys: the model as it was, with the nominal truck fitted on half 0,
  // and with the chosen effects as well.
  Eigen::VectorXd real, model, sigma, calibrated, after;
  Diagnosis diagnosis;
  // The chosen effects added to the model at the magnitudes fitted on half 0, judged on half 1.
  std::vector<ChannelResidual> channels;
  // Held-out half, re-simulated: RMS z and chi-square of the model as it was (raw), with the
  // nominal truck fitted (before: the gap the effects are asked to explain) and with the effects.
  double residual_raw = 0, residual_before = 0, residual_after = 0;
  double chi2_raw = 0, chi2_before = 0, chi2_after = 0;
  double null_chi2_mean = 0, null_chi2_sd = 0;  // the library's, for the same half
  std::size_t held_out = 0;                     // valid held-out features
  std::vector<UnmatchedChannel> unmatched;
  // Why no effect is named although one may fit: the runs' caveats, or a re-simulation with it
  // that did not lower the held-out residual.
  std::string withheld;
};

GapResult run_gap(const ModelLibrary& lib, const std::vector<RealRun>& runs, const j1939::Database& db, const GapOptions& options);

// The gap the named effects are asked to explain: the held-out chi-square the truck fitted alone
// leaves beyond the noise drives' mean, visible beyond four of their standard deviations (at
// least 40). Its shrink is the share of it the effects removed (0 when it is not visible).
bool gap_visible(const GapResult& g);
double gap_shrink(const GapResult& g);

// Simulates each (scenario, seed) into features on `jobs` threads; results in task order.
struct SimTask {
  sim::Scenario scenario;
  std::uint64_t seed = 1;
  const RunLayout* layout = nullptr;
};
// With `progress`, a line at most every 5 s: how many are done and about how long the rest takes.
std::vector<RecordedRun> simulate_all(const std::vector<SimTask>& tasks, const j1939::Database& db, unsigned jobs,
                                      const std::function<void(const std::string&)>& progress = {});

}  // namespace roadload::gap
