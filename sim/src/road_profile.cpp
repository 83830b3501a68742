#include "roadload/sim/road_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "roadload/sim/random.hpp"

namespace roadload::sim {
namespace {

constexpr double kN0_cycles_per_m = 0.1;  // ISO 8608 reference spatial frequency
// Separate streams so that switching joints on or off leaves the random roughness unchanged.
constexpr std::uint64_t kRoughnessStream = 0x524f554748ULL;
constexpr std::uint64_t kJointStream = 0x4a4f494e54ULL;

double interpolate(std::span<const double> z, double start_m, double dx_m, double x_m) {
  const double u = (x_m - start_m) / dx_m;
  if (!(u > 0.0)) return z.front();
  if (u >= static_cast<double>(z.size() - 1)) return z.back();
  const auto i = static_cast<std::size_t>(u);
  const double t = u - static_cast<double>(i);
  return z[i] + t * (z[i + 1] - z[i]);
}

// Integral of the interpolated profile over [a_m, b_m]: it is linear between grid points (and
// constant outside the grid), so the trapezoid between consecutive breakpoints is exact.
double integral_m2(std::span<const double> z, double start_m, double dx_m, double a_m, double b_m) {
  double sum = 0.0;
  double p = a_m;
  for (double k = std::floor((a_m - start_m) / dx_m) + 1.0;; k += 1.0) {
    const double q = std::min(start_m + k * dx_m, b_m);
    sum += (q - p) * 0.5 * (interpolate(z, start_m, dx_m, p) + interpolate(z, start_m, dx_m, q));
    if (q >= b_m) return sum;
    p = q;
  }
}

// w = 2 makes the slope white: G_s = (2 pi n0)^2 G_d(n0), so a leaky integrator of white slope gives
// the n^-2 law in O(1) per sample. The leak (n_low) only bounds the variance at very long
// wavelengths. One normal is drawn per sample whatever the G_d, so a segment's G_d does not shift
// the noise of the segments after it.
void add_roughness(std::vector<double>& z, std::span<const ProfileSegment> segments, double start_m, double dx_m,
                   double n_low_cycles_per_m, Rng rng) {
  const double leak = std::exp(-2.0 * std::numbers::pi * n_low_cycles_per_m * dx_m);
  const double slope_scale = 2.0 * std::numbers::pi * kN0_cycles_per_m / std::sqrt(2.0 * dx_m);
  std::size_t seg = 0;
  double height_m = 0.0;
  for (std::size_t i = 1; i < z.size(); ++i) {
    const double x_m = start_m + static_cast<double>(i - 1) * dx_m;  // the cell the slope spans
    while (seg + 1 < segments.size() && x_m >= segments[seg + 1].start_m) ++seg;
    const double gd_m3 = segments.empty() ? 0.0 : segments[seg].gd_n0_m3;
    // Discrete white slope with one-sided PSD G_s up to 1/(2 dx): variance G_s / (2 dx).
    const double slope = slope_scale * std::sqrt(gd_m3) * rng.normal();
    height_m = leak * height_m + dx_m * slope;
    z[i] = height_m;
  }
}

// A sawcut is narrower than the grid: each sample takes the gap's share of its cell, so the dip
// keeps its area (width x depth), which is what a footprint average sees of it.
void add_gap(std::vector<double>& z, double start_m, double dx_m, double joint_m, const JointSpec& joint) {
  const double lo_m = joint_m - 0.5 * joint.gap_width_m;
  const double hi_m = joint_m + 0.5 * joint.gap_width_m;
  const double first = std::max(0.0, std::floor((lo_m - start_m) / dx_m + 0.5));
  for (auto i = static_cast<std::size_t>(first); i < z.size(); ++i) {
    const double cell_lo_m = start_m + (static_cast<double>(i) - 0.5) * dx_m;
    if (cell_lo_m >= hi_m) return;
    const double overlap_m = std::min(hi_m, cell_lo_m + dx_m) - std::max(lo_m, cell_lo_m);
    if (overlap_m > 0.0) z[i] -= joint.gap_depth_m * overlap_m / dx_m;
  }
}

// Faulting: each slab rises by faulting_m from its start to its end, and the next slab starts
// faulting_m lower (the approach slab is higher than the leave slab, as a faulted joint is measured).
// The steps thus never accumulate into a ramp: a sawtooth with lines at k V / L rolling off as 1/k.
// Curl lifts both slab edges by curl_m over the centre, z = curl (2 xi / L - 1)^2.
void add_slabs(std::vector<double>& z, double start_m, double dx_m, const ProfileSegment& seg, Rng& rng,
               std::vector<double>& joints_m) {
  const JointSpec& joint = seg.joints;
  // Beyond a quarter slab the jittered joints could cross.
  const double jitter_m = std::min(joint.jitter_m, 0.25 * joint.spacing_m);
  std::vector<double> edges_m{seg.start_m};
  for (double k = 1.0; seg.start_m + k * joint.spacing_m + jitter_m < seg.end_m; k += 1.0) {
    edges_m.push_back(seg.start_m + k * joint.spacing_m + rng.uniform(-jitter_m, jitter_m));
  }
  edges_m.push_back(seg.end_m);
  joints_m.insert(joints_m.end(), edges_m.begin() + 1, edges_m.end() - 1);

  std::size_t slab = 0;
  const double first = std::max(0.0, std::ceil((seg.start_m - start_m) / dx_m));
  for (auto i = static_cast<std::size_t>(first); i < z.size(); ++i) {
    const double x_m = start_m + static_cast<double>(i) * dx_m;
    if (x_m >= seg.end_m) break;
    while (x_m >= edges_m[slab + 1]) ++slab;
    const double s = (x_m - edges_m[slab]) / (edges_m[slab + 1] - edges_m[slab]);
    z[i] += joint.curl_m * (2.0 * s - 1.0) * (2.0 * s - 1.0) + joint.faulting_m * (s - 0.5);
  }
  for (std::size_t j = 1; j + 1 < edges_m.size(); ++j) add_gap(z, start_m, dx_m, edges_m[j], joint);
}

}  // namespace

double iso8608_class_gd_m3(char cls) {
  if (cls < 'A' || cls > 'H') return std::numeric_limits<double>::quiet_NaN();
  // Factor-4 ladder of class centres (geometric means), not the upper bounds some generators use.
  return std::ldexp(16e-6, 2 * (cls - 'A'));
}

RoadProfile RoadProfile::generate(std::span<const ProfileSegment> segments, double start_m, double end_m, std::uint64_t seed,
                                  const ProfileOptions& options) {
  const double dx_m = options.dx_m;
  // The tolerance keeps an end on the grid from adding a sample through rounding.
  const double cells = std::max(0.0, std::ceil((end_m - start_m) / dx_m - 1e-9));
  std::vector<double> z(static_cast<std::size_t>(cells) + 1, 0.0);
  add_roughness(z, segments, start_m, dx_m, options.n_low_cycles_per_m, Rng(seed, kRoughnessStream));
  std::vector<double> joints_m;
  Rng joint_rng(seed, kJointStream);
  for (const auto& seg : segments) {
    if (seg.joints.spacing_m > 0.0) add_slabs(z, start_m, dx_m, seg, joint_rng, joints_m);
  }
  return RoadProfile(std::move(z), std::move(joints_m), start_m, dx_m, options.footprint_m);
}

RoadProfile RoadProfile::from_samples(std::vector<double> heights_m, double start_m, double dx_m, double footprint_m) {
  if (heights_m.empty()) heights_m.push_back(0.0);
  return RoadProfile(std::move(heights_m), {}, start_m, dx_m, footprint_m);
}

// A truck tire bridges features shorter than its contact patch; a moving average over the footprint
// is the simplest envelope that does (it nulls wavelengths of one footprint and its submultiples).
RoadProfile::RoadProfile(std::vector<double> raw, std::vector<double> joints_m, double start_m, double dx_m, double footprint_m)
    : raw_(std::move(raw)), joints_m_(std::move(joints_m)), start_m_(start_m), dx_m_(dx_m) {
  if (!(footprint_m > 0.0)) {
    enveloped_ = raw_;
    return;
  }
  enveloped_.resize(raw_.size());
  for (std::size_t i = 0; i < raw_.size(); ++i) {
    const double x_m = start_m_ + static_cast<double>(i) * dx_m_;
    enveloped_[i] = integral_m2(raw_, start_m_, dx_m_, x_m - 0.5 * footprint_m, x_m + 0.5 * footprint_m) / footprint_m;
  }
}

double RoadProfile::height_m(double x_m) const { return interpolate(raw_, start_m_, dx_m_, x_m); }

double RoadProfile::enveloped_height_m(double x_m) const { return interpolate(enveloped_, start_m_, dx_m_, x_m); }

double RoadProfile::end_m() const { return start_m_ + static_cast<double>(raw_.size() - 1) * dx_m_; }

}  // namespace roadload::sim
