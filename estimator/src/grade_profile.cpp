#include "roadload/grade_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "roadload/grade_error_scale.hpp"
#include "roadload/numbers.hpp"
#include "roadload/running_stats.hpp"

namespace roadload {
namespace {

// A slope needs three bins at least: two give a difference with nothing to check it against.
constexpr std::size_t kMinWindowBins = 3;

// A fix placed on the route: where along it, and the road's height there.
struct Placed {
  double s_m;
  double height_m;
};

// Bins are bin_m long from the route's start; the last one ends at the route's end (half a bin
// to one and a half long: a sliver would hold no fix), its centre in the middle.
std::size_t bin_count(double length_m, double bin_m) { return static_cast<std::size_t>(std::max(1.0, std::round(length_m / bin_m))); }

std::vector<GradeBin> make_bins(double length_m, double bin_m) {
  const std::size_t n = bin_count(length_m, bin_m);
  std::vector<GradeBin> bins(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double lo_m = static_cast<double>(k) * bin_m;
    bins[k].s_m = 0.5 * (lo_m + (k + 1 == n ? length_m : lo_m + bin_m));
  }
  return bins;
}

std::size_t bin_of(double s_m, double bin_m, std::size_t bins) {
  const auto k = static_cast<std::size_t>(std::max(0.0, std::floor(s_m / bin_m)));
  return std::min(k, bins - 1);
}

// d(atan x)/dx: a slope's standard error as the angle's.
double angle_sigma(double slope, double slope_sigma) { return slope_sigma / (1.0 + slope * slope); }

std::optional<Placed> place(const RouteGeometry& route, const GnssFix& f, double antenna_height_m, const GradeConfig& cfg,
                            GnssFixCounts& n) {
  // A 2-D fix holds its height at a guess; a NaN coordinate is a receiver without a solution.
  const bool finite = std::isfinite(f.lat_deg) && std::isfinite(f.lon_deg) && std::isfinite(f.alt_m);
  if (static_cast<int>(f.mode) < static_cast<int>(GnssFixMode::fix_3d) || !finite) {
    ++n.no_3d_fix;
    return std::nullopt;
  }
  if (f.hdop > cfg.max_hdop) {
    ++n.poor_hdop;
    return std::nullopt;
  }
  const RouteGeometry::Projection p = route.project(f.lat_deg, f.lon_deg);
  if (p.offset_m > cfg.max_offset_m) {
    ++n.off_route;
    return std::nullopt;
  }
  if (p.s_m < 0 || p.s_m > route.length_m()) {
    ++n.beyond_ends;
    return std::nullopt;
  }
  ++n.used;
  return Placed{p.s_m, f.alt_m - antenna_height_m};
}

// One past the last fix of the pass starting at `start`. The direction is known once the truck
// has covered reversal_m; the pass ends at its farthest point once the truck is reversal_m back
// from it (a turn, or a jump back after a loop off the route).
std::size_t pass_end(const std::vector<Placed>& track, std::size_t start, double reversal_m) {
  std::size_t lo = start, hi = start;
  int dir = 0;
  for (std::size_t i = start + 1; i < track.size(); ++i) {
    const double s_m = track[i].s_m;
    if (s_m > track[hi].s_m) hi = i;
    if (s_m < track[lo].s_m) lo = i;
    if (dir == 0) {
      if (track[hi].s_m - track[lo].s_m <= reversal_m) continue;
      dir = hi > lo ? 1 : -1;  // the later extreme is where the truck is heading
    }
    const std::size_t far = dir > 0 ? hi : lo;
    if (dir * (track[far].s_m - s_m) > reversal_m) return far + 1;
  }
  return track.size();
}

std::vector<std::vector<Placed>> split_passes(const std::vector<Placed>& track, double reversal_m) {
  std::vector<std::vector<Placed>> passes;
  for (std::size_t start = 0; start < track.size();) {
    const std::size_t end = pass_end(track, start, reversal_m);
    const auto first = track.begin() + static_cast<std::ptrdiff_t>(start);
    passes.emplace_back(first, first + static_cast<std::ptrdiff_t>(end - start));
    start = end;
  }
  return passes;
}

// The pass's mean height per bin (NaN where it has no fix): each pass counts once per bin,
// however long it spent there.
std::vector<double> pass_heights(const std::vector<Placed>& pass, double bin_m, std::size_t bins) {
  std::vector<double> sum_m(bins, 0.0);
  std::vector<std::size_t> count(bins, 0);
  for (const Placed& p : pass) {
    const std::size_t k = bin_of(p.s_m, bin_m, bins);
    sum_m[k] += p.height_m;
    ++count[k];
  }
  std::vector<double> mean_m(bins, kNaN);
  for (std::size_t k = 0; k < bins; ++k) {
    if (count[k] > 0) mean_m[k] = sum_m[k] / static_cast<double>(count[k]);
  }
  return mean_m;
}

struct Window {
  std::size_t first, last;  // inclusive bin indices
  std::size_t size() const { return last - first + 1; }
};

// The bins whose centres lie within +-base of bin k's, cut at the route's ends.
Window window_of(std::size_t k, std::size_t bins, const GradeConfig& cfg) {
  const auto half = static_cast<std::size_t>(std::floor(cfg.base_m / cfg.bin_m + 1e-9));
  return {k > half ? k - half : 0, std::min(k + half, bins - 1)};
}

// Least-squares slope = sum of w_j h_j over the window: the weights depend on positions only.
std::vector<double> slope_weights_per_m(const std::vector<GradeBin>& bins, Window w) {
  double mean_s_m = 0;
  for (std::size_t j = w.first; j <= w.last; ++j) mean_s_m += bins[j].s_m;
  mean_s_m /= static_cast<double>(w.size());
  double sxx_m2 = 0;
  for (std::size_t j = w.first; j <= w.last; ++j) sxx_m2 += (bins[j].s_m - mean_s_m) * (bins[j].s_m - mean_s_m);
  std::vector<double> weights;
  for (std::size_t j = w.first; j <= w.last; ++j) weights.push_back((bins[j].s_m - mean_s_m) / sxx_m2);
  return weights;
}

// The pass's slope over the window, if it has every bin of it: a pass with a gap would fit a
// different set of bins from the others, and its slope would not average with theirs.
std::optional<double> pass_slope(const std::vector<double>& heights_m, Window w, const std::vector<double>& weights) {
  double slope = 0;
  for (std::size_t j = w.first; j <= w.last; ++j) {
    if (!std::isfinite(heights_m[j])) return std::nullopt;
    slope += weights[j - w.first] * heights_m[j];
  }
  return slope;
}

// Mean and unbiased variance of a sample; the variance is NaN with fewer than two values.
struct Scatter {
  double mean = kNaN, variance = kNaN;
  std::size_t n = 0;
};

Scatter scatter_of(const std::vector<double>& x) {
  RunningStats r;
  for (double v : x) r.add(v);
  Scatter s;
  s.n = x.size();
  if (r.n > 0) s.mean = r.mean;
  if (r.n > 1) s.variance = r.m2 / static_cast<double>(r.n - 1);
  return s;
}

void fill_elevation(GradeBin& bin, const std::vector<std::vector<double>>& heights_m, std::size_t k) {
  std::vector<double> h_m;
  for (const auto& pass : heights_m) {
    if (std::isfinite(pass[k])) h_m.push_back(pass[k]);
  }
  const Scatter s = scatter_of(h_m);
  bin.elevation_passes = s.n;
  bin.elevation_m = s.mean;
  bin.elevation_sigma_m = std::sqrt(s.variance / static_cast<double>(s.n));  // NaN below two passes
}

// Bin k's grade from the passes' slopes; returns their scatter for the pooled standard error.
// Each pass's slope goes to slopes_by_pass[pass][k] (left NaN where the pass has none).
Scatter fill_grade(std::vector<GradeBin>& bins, const std::vector<std::vector<double>>& heights_m, std::size_t k,
                   const GradeConfig& cfg, std::vector<std::vector<double>>& slopes_by_pass) {
  GradeBin& bin = bins[k];
  bin.grade_rad = kNaN;
  bin.grade_sigma_rad = kNaN;
  const Window w = window_of(k, bins.size(), cfg);
  if (w.size() < kMinWindowBins) return {};
  const std::vector<double> weights = slope_weights_per_m(bins, w);
  std::vector<double> slopes;
  for (std::size_t p = 0; p < heights_m.size(); ++p) {
    if (auto b = pass_slope(heights_m[p], w, weights)) {
      slopes.push_back(*b);
      slopes_by_pass[p][k] = *b;
    }
  }
  bin.passes = slopes.size();
  if (slopes.size() < std::max<std::size_t>(cfg.min_passes, 1)) return {};
  const Scatter s = scatter_of(slopes);
  bin.grade_rad = std::atan(s.mean);
  return s;
}

// Standard error from the passes' slope variance pooled over +-sigma_pool_m, weighted by degrees
// of freedom, over this bin's number of passes.
void pool_grade_sigma(std::vector<GradeBin>& bins, const std::vector<Scatter>& slope_scatter, const GradeConfig& cfg) {
  const auto half = static_cast<std::size_t>(std::floor(cfg.sigma_pool_m / cfg.bin_m + 1e-9));
  for (std::size_t k = 0; k < bins.size(); ++k) {
    if (!std::isfinite(bins[k].grade_rad)) continue;
    double weighted = 0, dof = 0;
    for (std::size_t j = k > half ? k - half : 0; j <= std::min(k + half, bins.size() - 1); ++j) {
      if (!std::isfinite(slope_scatter[j].variance)) continue;
      const auto dof_j = static_cast<double>(slope_scatter[j].n - 1);
      weighted += dof_j * slope_scatter[j].variance;
      dof += dof_j;
    }
    if (dof == 0) {
      // One pass: no scatter to measure, the GNSS height's own error instead; without it no grade.
      if (std::isfinite(cfg.pass_slope_sigma)) {
        bins[k].grade_sigma_rad = angle_sigma(std::tan(bins[k].grade_rad), cfg.pass_slope_sigma);
      } else {
        bins[k].grade_rad = kNaN;
      }
      continue;
    }
    const double slope_sigma = std::sqrt(weighted / dof / static_cast<double>(slope_scatter[k].n));
    bins[k].grade_sigma_rad = angle_sigma(std::tan(bins[k].grade_rad), slope_sigma);
  }
}

}  // namespace

GradeProfile::GradeProfile(const GradeConfig& cfg, double length_m)
    : cfg_(cfg), length_m_(length_m), bins_(make_bins(length_m, cfg.bin_m)) {}

GradeProfile GradeProfile::from_survey(const RouteGeometry& route, double survey_sigma_m, const GradeConfig& cfg) {
  GradeProfile g(cfg, route.length_m());
  for (GradeBin& bin : g.bins_) {
    // Central difference over +-base, shortened at the ends rather than run off the survey.
    const double lo_m = std::max(bin.s_m - cfg.base_m, 0.0);
    const double hi_m = std::min(bin.s_m + cfg.base_m, route.length_m());
    const double slope = (route.elevation_m(hi_m) - route.elevation_m(lo_m)) / (hi_m - lo_m);
    bin.elevation_m = route.elevation_m(bin.s_m);
    bin.elevation_sigma_m = survey_sigma_m;
    bin.grade_rad = std::atan(slope);
    bin.grade_sigma_rad = angle_sigma(slope, std::sqrt(2.0) * survey_sigma_m / (hi_m - lo_m));
  }
  return g;
}

GradeProfile GradeProfile::from_gnss(const RouteGeometry& route, std::span<const GnssTrack> tracks, const GradeConfig& cfg) {
  GradeProfile g(cfg, route.length_m());
  std::vector<std::vector<double>> heights_m;  // [pass][bin]
  for (const GnssTrack& track : tracks) {
    std::vector<Placed> placed;
    for (const GnssFix& f : track.fixes) {
      if (auto p = place(route, f, track.antenna_height_m, cfg, g.fixes_)) placed.push_back(*p);
    }
    for (const auto& pass : split_passes(placed, cfg.reversal_m)) {
      heights_m.push_back(pass_heights(pass, cfg.bin_m, g.bins_.size()));
    }
  }
  g.passes_ = heights_m.size();
  std::vector<Scatter> slope_scatter(g.bins_.size());
  std::vector<std::vector<double>> slopes_by_pass(heights_m.size(), std::vector<double>(g.bins_.size(), kNaN));
  for (std::size_t k = 0; k < g.bins_.size(); ++k) {
    fill_elevation(g.bins_[k], heights_m, k);
    slope_scatter[k] = fill_grade(g.bins_, heights_m, k, cfg, slopes_by_pass);
  }
  pool_grade_sigma(g.bins_, slope_scatter, cfg);
  const GradeErrorScaleConfig scale{cfg.bin_m, cfg.correlation_block_m};
  if (auto l = measured_grade_error_correlation_m(slopes_by_pass, scale)) g.error_correlation_m_ = *l;
  return g;
}

std::size_t GradeProfile::bins_with_grade() const {
  return static_cast<std::size_t>(
      std::count_if(bins_.begin(), bins_.end(), [](const GradeBin& b) { return std::isfinite(b.grade_rad); }));
}

double GradeProfile::interpolate(double s_m, double GradeBin::*field) const {
  if (!(s_m >= 0 && s_m <= length_m_)) return kNaN;
  if (s_m <= bins_.front().s_m) return bins_.front().*field;
  if (s_m >= bins_.back().s_m) return bins_.back().*field;
  const std::size_t k = std::min(bin_of(s_m - bins_.front().s_m, cfg_.bin_m, bins_.size()), bins_.size() - 2);
  const double w = (s_m - bins_[k].s_m) / (bins_[k + 1].s_m - bins_[k].s_m);
  // A NaN neighbour gives NaN even at w = 0: no value is made up next to a bin without one.
  return bins_[k].*field + w * (bins_[k + 1].*field - bins_[k].*field);
}

std::optional<GradeProfile> GradeProfile::from_bins(double route_length_m, std::vector<GradeBin> bins, double base_m,
                                                    double error_correlation_m) {
  if (bins.size() < 2) return std::nullopt;
  GradeConfig cfg;
  cfg.bin_m = bins[1].s_m - bins[0].s_m;
  if (!(cfg.bin_m > 0)) return std::nullopt;
  cfg.base_m = std::max(base_m, cfg.bin_m);
  GradeProfile g(cfg, route_length_m);
  if (g.bins_.size() != bins.size()) return std::nullopt;
  for (std::size_t k = 0; k < bins.size(); ++k) {
    if (std::abs(g.bins_[k].s_m - bins[k].s_m) > 0.05 * cfg.bin_m) return std::nullopt;
  }
  g.bins_ = std::move(bins);
  if (error_correlation_m >= cfg.bin_m && std::isfinite(error_correlation_m)) g.error_correlation_m_ = error_correlation_m;
  return g;
}

double GradeProfile::error_correlation_m() const {
  return std::isnan(error_correlation_m_) ? 5.0 / 6.0 * cfg_.base_m : error_correlation_m_;
}

double GradeProfile::grade_rad(double s_m) const { return interpolate(s_m, &GradeBin::grade_rad); }
double GradeProfile::grade_sigma_rad(double s_m) const { return interpolate(s_m, &GradeBin::grade_sigma_rad); }
double GradeProfile::elevation_m(double s_m) const { return interpolate(s_m, &GradeBin::elevation_m); }

}  // namespace roadload
