#pragma once
// A route's grade and its uncertainty, per distance bin along the route: from a survey (the
// route's own elevations with a stated elevation sigma) or from the GNSS heights of several
// passes in either direction, averaged as the seed report did on TH 10 (Chapter 5). Grade is the
// largest error source of the force balance: 0.1 % of grade on the 36 t truck is 356 N, i.e.
// 0.001 in CRR, so the profile carries a standard error that the force balance can use.
//
// GNSS method: each fix is projected onto the route polyline; fixes off the route, beyond its
// ends or without a 3-D fix are counted and dropped. A track (one recording) is cut into passes
// where the travel along the route reverses. Each pass is averaged per bin first (a slow pass
// must not outweigh a fast one), then the passes are averaged per bin. Grade at a bin is the
// least-squares slope over the bins within +-base of the heights averaged over the passes that
// have every one of those bins (the mean of those passes' own slopes: the fit is linear). Its
// standard error is the scatter of the passes' slopes over sqrt(passes): the between-pass
// covariance of the bin heights, over the number of passes, propagated through the slope fit.
// Per-bin covariance rather than variance because a pass's height error is correlated over
// minutes: mostly an offset, which moves every bin and not the slope.
// Bins with fewer than `min_passes` passes have no grade (NaN): never guessed.
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"

namespace roadload {

// Needs bin_m > 0 and base_m >= bin_m (three bins to a slope); `roadload grade` checks both.
struct GradeConfig {
  double bin_m = 10.0;         // a second at 30 mph: several fixes per pass and bin at 10 Hz
  double base_m = 30.0;        // slope over +-30 m, as RouteGeometry: shorter bases amplify height noise
  std::size_t min_passes = 2;  // one pass has no scatter, hence no standard error
  double max_offset_m = 15.0;  // a few lanes from the surveyed line: farther is another road
  double max_hdop = 5.0;       // beyond this the height is worse than the grade it should give
  double reversal_m = 30.0;    // travel back this far along the route starts a new pass
  // The between-pass slope variance is pooled over bins within +-pool: two or three passes give
  // a variance with one or two degrees of freedom per bin, too noisy to weight a force balance.
  // The GNSS noise does not change over a few hundred metres. 0 keeps each bin's own.
  double sigma_pool_m = 100.0;
  // A slope's standard error where the passes give no scatter (one pass): what a GNSS height error
  // makes of a slope over the base. NaN: none, such bins have no standard error and no grade.
  double pass_slope_sigma = std::numeric_limits<double>::quiet_NaN();
  // The length over which the grade error's correlation is measured (grade_error_scale.hpp):
  // about a cell's, since the cells' means are what it must get right.
  double correlation_block_m = 600.0;
};

// One recording's fixes in time order, and the antenna's height above the road it stands on.
struct GnssTrack {
  std::span<const GnssFix> fixes;
  double antenna_height_m = 0.0;
};

struct GradeBin {
  double s_m = 0;                    // bin centre along the route
  double elevation_m = 0;            // ellipsoidal height of the road; NaN without data
  double elevation_sigma_m = 0;      // standard error; NaN with fewer than two passes
  double grade_rad = 0;              // NaN with fewer than min_passes passes
  double grade_sigma_rad = 0;        // standard error of grade_rad
  std::size_t passes = 0;            // passes in the grade (0 for a survey: not a drive)
  std::size_t elevation_passes = 0;  // passes with fixes in this bin
};

struct GnssFixCounts {
  std::size_t used = 0;
  std::size_t off_route = 0;    // farther than max_offset_m from the polyline
  std::size_t beyond_ends = 0;  // projected before its first point or after its last
  std::size_t no_3d_fix = 0;    // mode none or 2-D (height held, not measured), or not finite
  std::size_t poor_hdop = 0;    // hdop above max_hdop
};

class GradeProfile {
 public:
  // The survey's own grade: central difference over +-base (RouteGeometry's) with the two end
  // heights' independent errors of `survey_sigma_m` each.
  static GradeProfile from_survey(const RouteGeometry& route, double survey_sigma_m, const GradeConfig& cfg = {});
  static GradeProfile from_gnss(const RouteGeometry& route, std::span<const GnssTrack> tracks, const GradeConfig& cfg = {});
  // A profile written earlier (`roadload grade`): nothing when the bins are not this route's
  // bins at their own spacing (another route, or edited by hand). `base_m`: the slopes' +-base.
  // `error_correlation_m`: the one measured when it was built (NaN: none, the bound below).
  static std::optional<GradeProfile> from_bins(double route_length_m, std::vector<GradeBin> bins,
                                               double base_m = GradeConfig{}.base_m,
                                               double error_correlation_m = std::numeric_limits<double>::quiet_NaN());

  // Linear between bin centres; NaN off the route or where a bin involved has no value.
  double grade_rad(double s_m) const;
  double grade_sigma_rad(double s_m) const;
  double elevation_m(double s_m) const;

  std::span<const GradeBin> bins() const { return bins_; }
  const GnssFixCounts& fixes() const { return fixes_; }
  std::size_t passes() const { return passes_; }  // passes found in the tracks (0 for a survey)
  std::size_t bins_with_grade() const;
  const GradeConfig& config() const { return cfg_; }
  double length_m() const { return length_m_; }
  // The correlation length of a Gauss-Markov process standing in for the grade's error along the
  // road, chosen so a cell's mean carries the error the cell's mean grade has. Built from GNSS
  // passes: measured from their scatter (grade_error_scale.hpp). Otherwise a bound: a GNSS height
  // error that wanders like a random walk (diffusion D per metre) over the +-base window gives a
  // slope of variance 3 D / (5 base), a cell of length L a mean slope of variance D / L, and the
  // process gives that mean 2 l sigma^2 / L, so l = 5 base / 6. White height noise adds to a
  // bin's sigma and nothing to a cell's mean, so that is the longest honest length.
  double error_correlation_m() const;
  // NaN unless measured from passes or read from a profile file that recorded it.
  double measured_error_correlation_m() const { return error_correlation_m_; }

 private:
  GradeProfile(const GradeConfig& cfg, double length_m);
  double interpolate(double s_m, double GradeBin::*field) const;

  GradeConfig cfg_;
  double length_m_ = 0;
  std::vector<GradeBin> bins_;
  GnssFixCounts fixes_;
  std::size_t passes_ = 0;
  double error_correlation_m_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace roadload
