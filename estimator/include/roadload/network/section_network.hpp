#pragma once
// The network view's model (docs/fleet.md, "The statistical model"): each drive's CRR of a
// section is that section's CRR, plus what the drive shares over all its sections (its truck's
// tires, the same at every speed; its truck's drag error, which grows with the square of speed
// from nothing standing; the drive's own torque and weather errors), plus the cell's own error. Sections are fixed effects; the
// shared parts are random effects whose spreads the fleet's data tell. A section's difference from its neighbours then carries only
// the cells' own errors, as precise as the drives allow.
#include <cstddef>
#include <vector>

#include "roadload/network/mixed_model.hpp"

namespace roadload::network {

struct SectionObservation {
  std::size_t section = 0, drive = 0, truck = 0;
  double crr = 0;
  double crr_sigma = 0;  // the cell's own estimate of its error; weighs it against the others
  double speed_mps = 0;
};

struct SectionEstimate {
  double crr = 0, crr_sigma = 0;  // at the reference speed, for the fleet's mean truck
  double crr_lo = 0, crr_hi = 0;  // 90 %
};

struct TruckEffect {
  double offset = 0, offset_sd = 0;  // CRR added by this truck at every speed: its tires
  double drag = 0;                   // and at the reference speed by its drag error
};

struct SectionNetworkFit {
  bool fitted = false;
  double reference_speed_mps = 0;  // the observations' RMS speed: where the drag term is zero
  std::vector<SectionEstimate> sections;
  std::vector<TruckEffect> trucks;
  VarianceComponent cell, drive, truck, truck_drag;  // the spreads, CRR units; truck: the tires'
  double fleet_speed_slope = 0;                      // CRR per (v / v_ref)^2 - 1, the fleet's mean
  int evaluations = 0;
};

// What is known of the trucks before the fleet's data: log-normal priors on the spreads the data
// alone may not tell (a fleet of one truck cannot tell its tires from the road). Weak: a factor
// of e either way is one sigma, so twenty trucks' data outweigh them.
struct SectionNetworkPriors {
  // A truck's tires: +-5 % of 0.006 between makes of one size.
  double truck_sd = 3e-4;
  // Its drag error at the reference speed: 0.5 m2 of CdA at 25 m/s on 36 t is 0.0004.
  double truck_drag_sd = 4e-4;
  double log_sd = 1.0;
};

// `sections`, `drives`, `trucks`: the index ranges the observations use. A section without
// observations gets NaN; the fit needs more observations than sections plus one.
SectionNetworkFit fit_section_network(const std::vector<SectionObservation>& observations, std::size_t sections, std::size_t drives,
                                      std::size_t trucks, const SectionNetworkPriors& priors = {});

}  // namespace roadload::network
