#pragma once
// Steps 2-4 of the diagnosis as pure arithmetic on whitened residuals: where the gap lies, which
// candidate effect explains it (fitted on one half of the road, judged on the other) and its
// magnitude with an interval. No simulation here: the candidates arrive as responses already
// simulated (resimulate.hpp, library.hpp), so this part runs in a unit test in microseconds.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace roadload::gap {

struct FeatureKey {
  std::string run;      // the recording's label
  std::string channel;  // features.hpp
  std::string where;
  std::uint8_t half = 0;
};

// A candidate effect's response, whitened like the residuals: the features move by
// a u + b u^2 when the effect's magnitude moves by u from the model's own (`base`). a and b come
// from two simulations at base + u1 and base + u2.
struct Candidate {
  std::string name;
  std::string unit;
  double base = 0;
  double lo = 0, hi = 0;  // magnitudes a fit may take
  // Where the effect is met in practice (the catalog's range): a fit far outside it is not
  // believed (DecisionRule::range_tolerance).
  double realistic_lo = -std::numeric_limits<double>::infinity(), realistic_hi = std::numeric_limits<double>::infinity();
  Eigen::VectorXd a, b;
  // The most it removed from drives with nothing missing from the model but their truck (the
  // library's noise drives): an effect that fits noise must beat its own noise to be named.
  double null_gain = 0;
  // The nominal parameter that stands for it, when one does (a wrong declared mass is the
  // nominal mass): it is fitted and listed but never named, which would count it twice.
  std::string stood_for_by;

  static Candidate from_two(std::string name, std::string unit, double base, double lo, double hi, double m1,
                            const Eigen::VectorXd& d1, double m2, const Eigen::VectorXd& d2);
  Eigen::VectorXd response(double magnitude) const;
};

// A nominal parameter of the model's truck (nominal.hpp) as the fit sees it: linear, in units of
// its prior sigma, with a unit normal prior. Every fit moves these with the candidates.
struct NominalColumn {
  std::string name, unit;
  double value = 0, sigma = 0;  // the model's value and its prior sigma
  Eigen::VectorXd per_sigma;    // whitened response to one sigma
};

struct Problem {
  std::vector<FeatureKey> keys;
  Eigen::VectorXd z;  // (real - model) / noise; NaN where either side never saw the feature
  std::vector<Candidate> candidates;
  std::vector<NominalColumn> nominal;
};

// The nominal parameters fitted on half 0 (with the chosen effects, when any), 90 % intervals.
struct NominalFit {
  std::vector<double> value, lo, hi;  // in the parameters' units, Problem::nominal's order
  std::vector<double> shift_sigma;    // (value - model) / prior sigma
  double chi2_half1_before = 0;       // held-out chi-square of the model as it was
  double chi2_half1_after = 0;        // and with these values (linear in their responses)
};

struct Fit {
  std::vector<std::size_t> effects;       // indices into Problem::candidates
  std::vector<double> magnitude, lo, hi;  // fitted on both halves; 90 % interval
  std::vector<double> magnitude_half0;    // fitted on half 0 alone: what the held-out check uses
  double gain = 0;                        // chi-square removed on held-out data, both folds, minus the complexity penalty,
                                          // times the plausibility of the magnitudes and of the truck beside them
  double plausibility = 1;                // exp(-(d / tolerance)^2), d: distance outside the realistic range in its widths
  double truck_sigma = 0;                 // in prior sigmas (both halves' fit): the offset the truck factor penalises
                                          // most, else the one farthest from the model
  double truck_plausibility = 1;          // exp(-b^2) per offset, b: how far it lies beyond both
                                          // DecisionRule::truck_sigmas and the truck fitted alone
  double gain_truck_kept = 0;             // held-out gain with the truck kept where it fits alone (when
                                          // truck_plausibility < 1): the gain is at least the smaller of it and the free one
  bool scored_truck_kept = false;         // the gain is that one
};

struct WhereItem {
  std::string run, channel, where;
  std::size_t features = 0;
  double excess = 0;        // sum z^2 minus its noise expectation
  double significance = 0;  // excess / sqrt(2 n): standard deviations above noise
  double worst_z = 0;       // the largest |z| inside, and where
  std::string worst_where;
};

struct DecisionRule {
  double null_gain = 100.0;       // held-out chi-square a candidate must remove to be named
  double null_factor = 2.0;       // and this many times its own Candidate::null_gain
  double pair_gain = 50.0;        // and a second effect beyond the first
  double pair_share = 0.01;       // and at least this share of the first's gain: less is the first's model error
  double penalty = 2.0;           // per fitted magnitude, AIC-like
  std::size_t pair_pool = 6;      // the best singles, itself left out, tried beside the named one
  double range_tolerance = 0.25;  // of the realistic range's width, outside it
  // A fit that needs the truck farther than this from the model, in its priors' sigmas, and
  // farther than the truck fitted alone, explains the drive with a truck the spreads hardly ever
  // draw: its gain is scaled by exp(-b^2), b the excess beyond both.
  double truck_sigmas = 3.0;
  // Of a gap visible above the noise, the share the named effects must remove once re-simulated:
  // one that removes a sliver of a large gap is not its explanation, and a gap mostly unexplained
  // bends every fit beside it.
  double min_shrink = 0.25;
};

struct Diagnosis {
  NominalFit nominal;            // the model's truck fitted to this one, before any effect
  std::vector<Fit> singles;      // every candidate, best first
  std::optional<Fit> best_pair;  // the named single (else the best) and the best second beside it
  std::optional<Fit> chosen;     // none: no candidate explains the gap significantly
  // Single fits of other candidates that would be named on their own and came within
  // rival_margin() of the first chosen effect's: the drives cannot tell them from it. Best first.
  std::vector<Fit> rivals;
  std::vector<WhereItem> where;  // most significant first
  std::size_t features = 0;
  double chi2 = 0;  // of the residual before any effect
};

Diagnosis diagnose(const Problem& p, const DecisionRule& rule = {});

// How close another candidate's gain must come to the named one's for the drives not to tell
// them apart: as much as noise alone gives either (its Candidate::null_gain), and at least the
// gain the rule takes as evidence at all.
double rival_margin(const Candidate& named, const Candidate& other, const DecisionRule& rule);

// One set of candidates fitted (with the nominal parameters beside them) and scored as diagnose
// scores it.
Fit fit_effects(const Problem& p, const std::vector<std::size_t>& set, const DecisionRule& rule = {});

// The nominal parameters fitted on half 0 beside a set of candidates at their half-0 magnitudes.
NominalFit fit_nominal(const Problem& p, const std::vector<std::size_t>& set, const std::vector<double>& magnitude_half0);

// Where a truck (offsets in prior sigmas) and effects stand, and where one Gauss-Newton step
// takes them: `z` is what their re-simulation left (whitened), the problem's responses (taken
// about the model's truck) the Jacobian, each effect's quadratic re-centred on its magnitude. The
// step is fitted on half 0, the nominal offsets' prior about where they stand.
struct Placement {
  std::vector<double> shift_sigma;
  std::vector<std::size_t> effects;     // indices into Problem::candidates
  std::vector<double> magnitude_half0;  // one per effect
};
Placement gauss_newton_step(const Problem& p, const Eigen::VectorXd& z, const Placement& from, const DecisionRule& rule = {});

// Groups by (run, channel), ranked by significance, each naming its worst place.
std::vector<WhereItem> locate(const std::vector<FeatureKey>& keys, const Eigen::VectorXd& z, std::size_t limit);

// RMS of the valid z in one half (255: both).
double rms(const Eigen::VectorXd& z, const std::vector<FeatureKey>& keys, std::uint8_t half);

}  // namespace roadload::gap
