#pragma once
// The road under the tires: one longitudinal height profile, sampled on a regular grid.
//
// Random roughness follows ISO 8608 (one-sided displacement PSD G_d(n) = G_d(n0) (n/n0)^-2,
// n0 = 0.1 cycle/m, waviness w = 2; class values are the geometric means of the factor-4 ladder).
// Jointed concrete (JPCP) adds faulting, sawcut gaps and slab curl on top; magnitudes and shapes are
// from docs/simulator-parameters.md, sections 6.1 and 6.4.
#include <cstdint>
#include <span>
#include <vector>

namespace roadload::sim {

// 'A'..'H' -> geometric-mean G_d(n0) in m^3 (16e-6 for A); NaN for any other character.
double iso8608_class_gd_m3(char cls);

// ISO 8608 (w = 2) <-> IRI: IRI [m/km] = 0.543 sqrt(G_d(n0) / 1e-6 m^3). The constant is the Golden
// Car's response to an n^-2 Gaussian profile (docs/simulator-parameters.md, Sect. 6.1); iri_test
// checks it against iri_m_per_km (iri.hpp) on this module's own profiles.
double gd_from_iri_m3(double iri_m_per_km);
double iri_from_gd_m_per_km(double gd_n0_m3);

// Transverse joints of a jointed concrete pavement. Any magnitude 0 switches that term off.
struct JointSpec {
  double spacing_m = 0;   // nominal slab length; 0: no joints
  double faulting_m = 0;  // step at each joint, leave slab lower than approach slab
  double curl_m = 0;      // slab-edge lift above the slab centre (negative: edges down)
  double gap_width_m = 0.01;
  double gap_depth_m = 0.001;
  double jitter_m = 0.1;  // each joint moves uniformly within +-jitter_m of its nominal place
};

struct ProfileSegment {
  double start_m = 0;
  double end_m = 0;
  double gd_n0_m3 = 0;  // ISO 8608 G_d(n0); 0: no random roughness
  JointSpec joints;
};

struct ProfileOptions {
  double dx_m = 0.05;
  double footprint_m = 0.20;          // tire contact length for the enveloped profile; 0: enveloped = raw
  double n_low_cycles_per_m = 0.005;  // below this the random profile stops growing as n^-2
};

class RoadProfile {
 public:
  // Covers [start_m, end_m] (end rounded up to the grid); positions outside take the nearest end's
  // value. Segments are given in order and may leave gaps, where the random roughness continues
  // with the previous segment's G_d (the first segment's before it). The profile starts at height 0.
  // Joints: each concrete segment starts a new slab at its start_m; jittered joints stay inside it.
  static RoadProfile generate(std::span<const ProfileSegment> segments, double start_m, double end_m, std::uint64_t seed,
                              const ProfileOptions& options = {});
  // A given profile (measured, or synthetic for tests), heights at start_m + i * dx_m.
  static RoadProfile from_samples(std::vector<double> heights_m, double start_m, double dx_m, double footprint_m = 0.20);

  double height_m(double x_m) const;            // raw profile, linear interpolation
  double enveloped_height_m(double x_m) const;  // after the tire-footprint moving average
  double start_m() const { return start_m_; }
  double end_m() const;  // position of the last sample
  double dx_m() const { return dx_m_; }
  std::span<const double> raw_samples() const { return raw_; }
  std::span<const double> joint_positions_m() const { return joints_m_; }

 private:
  RoadProfile(std::vector<double> raw, std::vector<double> joints_m, double start_m, double dx_m, double footprint_m);

  std::vector<double> raw_;
  std::vector<double> enveloped_;
  std::vector<double> joints_m_;
  double start_m_;
  double dx_m_;
};

}  // namespace roadload::sim
