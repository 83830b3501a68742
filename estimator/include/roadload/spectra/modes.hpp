#pragma once
// Vibration modes in a PSD, and the joint line of jointed concrete in a spatial PSD.
//
// Peaks: local maxima with their prominence (height above the higher of the two lowest points
// between the peak and the nearest higher ground on either side, as scipy.signal.peak_prominences)
// and width at half prominence. A PSD spans decades, so a peak is kept by its prominence relative
// to its height. Labels by band: rigid body below 4 Hz, bounce/pitch 4-5 Hz, tandem 7-13 Hz,
// axle hop 13-16 Hz, roll about 17 Hz (seed report Figs. 6.6-6.11).
//
// Joint line: panels of length L hit the tires every L metres, a comb of lines at h / L cycles/m.
// Every channel's spatial density is taken over its local median background (log ratio), and the
// channels averaged: each sensor sees the same joints through its own path. A candidate L scores
// the sum of that log ratio at its harmonics over sqrt(harmonics): a subharmonic (2L) finds only
// every other line and a multiple (L/2) half as many lines, so the true L wins by sqrt(2). Its
// significance is its distance from the median of all candidates' scores in robust standard
// deviations (1.4826 MAD): on a pavement without joints no candidate stands out. L is refined by
// least squares through the strong harmonics' interpolated peaks.
// A blind search looks at ~2,000 candidates and needs 6 sigma not to find joints in asphalt. Where
// the pavement inventory gives a panel length (the route's joint_spacing_m), the search is held to
// +-15 % of it and 3.5 sigma suffices: the data then confirms the line and measures L.
#include <span>
#include <string_view>
#include <vector>

namespace roadload::spectra {

struct Peak {
  double freq = 0;  // in the density's own unit (Hz, or cycles/m)
  double density = 0;
  double prominence = 0;
  double width = 0;  // at half prominence
  std::string_view label;
  int joint_harmonic = 0;  // h when the peak is the joint line's h-th harmonic, else 0
};

struct PeakConfig {
  double min_freq = 0.3;
  double max_freq = 40;
  double min_relative_prominence = 0.5;  // prominence / height: at least twice its surroundings
  std::size_t max_peaks = 8;             // the most prominent
};

std::vector<Peak> find_peaks(std::span<const double> density, double bin, const PeakConfig& config = {});
std::string_view mode_band(double freq_hz);

struct JointConfig {
  double min_panel_m = 2.5;
  double max_panel_m = 12.0;
  double max_cpm = 2.0;              // harmonics up to this spatial frequency
  std::size_t background_bins = 12;  // the median background over +- this many bins (0.037 cycles/m)
  double min_significance = 6.0;     // blind: robust standard deviations of the bins' scatter
  double expected_panel_m = 0;       // from the pavement inventory; 0: blind search
  double expected_window = 0.15;     // +- this fraction of expected_panel_m
  double min_guided_significance = 3.5;
};

struct JointLine {
  bool found = false;
  double panel_m = 0;
  double spatial_cpm = 0;   // 1 / panel_m
  double significance = 0;  // of the best candidate, found or not
  int harmonics = 0;        // used in the refinement
};

// `channels`: spatial densities on bins of bin_cpm from 0, all of one length.
JointLine find_joint_line(std::span<const std::vector<double>> channels, double bin_cpm, const JointConfig& config = {});

// Marks peaks at h x joint_hz (within one bin) as the joint line's harmonics.
void label_joint_harmonics(std::vector<Peak>& peaks, double joint_hz, double bin_hz);

}  // namespace roadload::spectra
