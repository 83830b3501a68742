#pragma once
// How far along the road a GNSS-built grade's error stays correlated, measured from the passes
// themselves. The force balance carries the grade's error as a Gauss-Markov process (CrrFilter);
// what a cell's CRR inherits from it is the error of the cell's mean grade, 2 l sigma^2 / L for
// a process of correlation length l. The passes' slopes scatter about their mean with the same
// correlation as the mean's error, so the variance of their means over blocks of a cell's length,
// against their point variance, gives l for that length: white height noise, whose slopes
// cancel over a block, counts for little; a receiver's slow wander, which does not, counts fully.
#include <cstddef>
#include <optional>
#include <vector>

namespace roadload {

struct GradeErrorScaleConfig {
  double bin_m = 10.0;
  double block_m = 600.0;      // a cell's length: the scale intervals are judged at
  std::size_t min_blocks = 8;  // independent blocks (summed over passes) for a variance
};

// slopes[pass][bin]: each pass's slope at each bin (NaN where the pass has none); at least two
// passes. Nothing when too few whole blocks exist to measure a variance; otherwise the
// correlation length, between a bin and half a block.
std::optional<double> measured_grade_error_correlation_m(const std::vector<std::vector<double>>& slopes,
                                                         const GradeErrorScaleConfig& cfg);

// The share of a Gauss-Markov process's point variance left in its mean over a length L:
// 2 (l/L) (1 - (l/L)(1 - exp(-L/l))).
double gauss_markov_mean_variance_share(double correlation_m, double length_m);

}  // namespace roadload
