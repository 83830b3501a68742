#pragma once
// A linear mixed model fitted by restricted maximum likelihood (REML): fixed effects (here the
// sections' CRR) and random effects in groups (a truck's tires, a drive's shared errors), each
// group with a variance the data tell. Solved through Henderson's mixed-model equations, whose
// size is the number of effects, not of observations; every observation touches a few of them.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

namespace roadload::network {

// One observation's non-zero entries of a design row: (column or level, value).
using SparseEntries = std::vector<std::pair<std::size_t, double>>;

struct RandomTerm {
  std::string name;
  std::size_t levels = 0;
  // A log-normal prior on the term's sd, when the data alone may not tell it: one truck cannot
  // tell its tires from the road, and the vehicle files say how far trucks' tires spread.
  double prior_sd = 0;      // its median; 0: no prior
  double prior_log_sd = 0;  // the sd of log(sd)
};

struct MixedModel {
  std::size_t fixed_columns = 0;
  std::vector<RandomTerm> terms;
  struct Observation {
    double y = 0;
    double weight = 1;     // relative precision: its residual variance is sigma^2 / weight
    SparseEntries fixed;   // (fixed column, value)
    SparseEntries random;  // (term, level) flattened by random_index(); value: the covariate
  };
  std::vector<Observation> observations;

  // Where level `level` of term `term` sits among all random effects.
  std::size_t random_index(std::size_t term, std::size_t level) const;
};

struct VarianceComponent {
  std::string name;
  double sd = 0;
  double sd_lo = 0, sd_hi = 0;  // 90 % interval from the curvature of the REML surface
};

struct MixedModelFit {
  Eigen::VectorXd fixed;      // estimates
  Eigen::MatrixXd fixed_cov;  // their covariance, the random effects' uncertainty included
  Eigen::VectorXd random;     // predicted random effects (BLUPs), by random_index()
  Eigen::VectorXd random_sd;  // their prediction error
  VarianceComponent residual;
  std::vector<VarianceComponent> terms;
  double minus2_reml = 0;
  int evaluations = 0;
  bool converged = false;
};

// Needs at least one observation more than fixed columns; the fixed design must have full rank
// (every fixed column observed), else the fit's `converged` is false and its estimates are NaN.
MixedModelFit fit_reml(const MixedModel& model);

}  // namespace roadload::network
