#pragma once
// The road's roughness as the truck's speed sees it. Each tire climbs and descends the profile's
// heights h_i; the work m g h it stores comes back, so the speed carries a ripple
//   dv = -sum_i F_i h_i / (m v)
// that a force balance would otherwise read as force noise (white at a tick, nothing over a
// cell: the heights are bounded). The profile follows ISO 8608 (displacement PSD G_d(n0) (n/n0)^-2,
// n0 = 0.1 cycle/m) below the wavelengths the grade profile resolves, taken here as a first-order
// Gauss-Markov height along the road with correlation length L: its PSD 4 s^2 L / (1 + (2 pi n L)^2)
// meets the ISO slope at high n when s^2 = pi^2 L n0^2 G_d(n0).
#include <span>

namespace roadload::model {

// ISO 8608 (waviness 2) G_d(n0) from IRI, m^3: IRI = 0.543 sqrt(G_d(n0) / 1e-6 m^3) for a Gaussian
// n^-2 profile (Sayers' Golden Car response; docs/estimator.md).
double iso8608_gd_m3(double iri_m_per_km);

// The profile height's sigma for that roughness, correlated over `correlation_m`.
double roughness_height_sigma_m(double iri_m_per_km, double correlation_m);

struct AxleWeight {
  double behind_front_m = 0;
  double weight_n = 0;
};

// The truck's ripple: each axle's height is that process, the axles' correlated by exp(-d / L) at
// d apart, and the ripple their weighted sum, whose sigma times the speed is
// sqrt(sum_ij F_i F_j exp(-d_ij / L)) s_h / m. As a single Gauss-Markov process it is given the
// correlation length whose change over `step_m` (the distance between speed updates) is the sum's:
// the axles share the long waves but, over a short step, few of their changes, so the lumped
// process is smoother than any one axle's.
struct RoughnessRipple {
  double sigma_m2ps = 0;
  double correlation_m = 0;
};
RoughnessRipple roughness_ripple(std::span<const AxleWeight> axles, double mass_kg, double height_sigma_m, double correlation_m,
                                 double step_m);

}  // namespace roadload::model
