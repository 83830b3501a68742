#include "roadload/spectra/modes.hpp"

#include <algorithm>
#include <cmath>

namespace roadload::spectra {

std::string_view mode_band(double f) {
  if (f < 4) return "rigid body";
  if (f < 5) return "bounce/pitch";
  if (f < 7) return "body";
  if (f < 13) return "tandem";
  if (f < 16) return "axle hop";
  if (f < 19) return "roll";
  return "structure";
}

std::vector<Peak> find_peaks(std::span<const double> d, double bin, const PeakConfig& config) {
  std::vector<Peak> out;
  const std::size_t n = d.size();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double f = static_cast<double>(k) * bin;
    if (f < config.min_freq || f > config.max_freq || !(d[k] > d[k - 1] && d[k] >= d[k + 1])) continue;
    double left_min = d[k], right_min = d[k];
    std::size_t i = k;
    while (i > 0 && d[i - 1] <= d[k]) left_min = std::min(left_min, d[--i]);
    i = k;
    while (i + 1 < n && d[i + 1] <= d[k]) right_min = std::min(right_min, d[++i]);
    const double prominence = d[k] - std::max(left_min, right_min);
    if (prominence < config.min_relative_prominence * d[k]) continue;
    // Width at half prominence, linear between bins.
    const double h = d[k] - prominence / 2;
    std::size_t l = k, r = k;
    while (l > 0 && d[l] > h) --l;
    while (r + 1 < n && d[r] > h) ++r;
    const double fl = d[l] < h ? static_cast<double>(l) + (h - d[l]) / (d[l + 1] - d[l]) : static_cast<double>(l);
    const double fr = d[r] < h ? static_cast<double>(r) - (h - d[r]) / (d[r - 1] - d[r]) : static_cast<double>(r);
    out.push_back({f, d[k], prominence, (fr - fl) * bin, mode_band(f), 0});
  }
  std::sort(out.begin(), out.end(), [](const Peak& a, const Peak& b) { return a.prominence > b.prominence; });
  if (out.size() > config.max_peaks) out.resize(config.max_peaks);
  std::sort(out.begin(), out.end(), [](const Peak& a, const Peak& b) { return a.freq < b.freq; });
  return out;
}

namespace {

// Mean over channels of each bin's log ratio to the median of the bins around it.
std::vector<double> log_ratio(std::span<const std::vector<double>> channels, std::size_t half) {
  const std::size_t n = channels.front().size();
  std::vector<double> out(n, 0.0), window;
  for (const auto& d : channels) {
    for (std::size_t j = 1; j < n; ++j) {
      const std::size_t lo = j > half ? j - half : 1, hi = std::min(n - 1, j + half);
      window.assign(d.begin() + static_cast<std::ptrdiff_t>(lo), d.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
      std::nth_element(window.begin(), window.begin() + static_cast<std::ptrdiff_t>(window.size() / 2), window.end());
      const double median = window[window.size() / 2];
      if (median > 0 && d[j] > 0) out[j] += std::log(d[j] / median) / static_cast<double>(channels.size());
    }
  }
  return out;
}

std::size_t nearest(const std::vector<double>& r, double pos) {
  return std::min(static_cast<std::size_t>(std::lround(pos)), r.size() - 1);
}

double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// A subharmonic (2L, 3L) that won on a body resonance at its fundamental: its other harmonics off
// the true comb carry no line. Returns the comb's spacing moved up to the true one.
double past_subharmonics(const std::vector<double>& lr, double k0, double top, double bin_cpm, const JointConfig& config) {
  for (bool moved = true; moved;) {
    moved = false;
    for (int m : {2, 3}) {
      double on = 0, off = 0;
      int n_on = 0, n_off = 0;
      for (int h = 2; h * k0 <= top; ++h) {
        (h % m == 0 ? on : off) += lr[nearest(lr, h * k0 / bin_cpm)];
        ++(h % m == 0 ? n_on : n_off);
      }
      if (n_on >= 2 && n_off >= 2 && m * k0 <= 1.0 / config.min_panel_m && off / n_off < 0.5 * on / n_on) {
        k0 *= m;
        moved = true;
        break;
      }
    }
  }
  return k0;
}

}  // namespace

JointLine find_joint_line(std::span<const std::vector<double>> channels, double bin_cpm, const JointConfig& config) {
  JointLine best;
  if (channels.empty() || channels.front().size() < 16) return best;
  // Each bin's best within one bin either side, less the median of that over the band: a candidate
  // whose harmonics fall between lines then scores about nothing rather than the max's own bias.
  const std::vector<double> raw = log_ratio(channels, config.background_bins);
  std::vector<double> lr(raw.size(), 0.0);
  for (std::size_t j = 1; j + 1 < raw.size(); ++j) lr[j] = std::max({raw[j - 1], raw[j], raw[j + 1]});
  const double top = std::min(config.max_cpm, bin_cpm * static_cast<double>(lr.size() - 2));
  const auto band_lo = static_cast<std::ptrdiff_t>(1.0 / config.max_panel_m / bin_cpm);
  const auto band_hi = static_cast<std::ptrdiff_t>(top / bin_cpm);
  const double bias = median_of(std::vector<double>(lr.begin() + band_lo, lr.begin() + band_hi));
  for (double& x : lr) x -= bias;
  std::size_t candidates = 0;
  double best_score = -1e300, best_k0 = 0;
  const bool guided = config.expected_panel_m > 0;
  const double k_lo = guided ? 1.0 / (config.expected_panel_m * (1 + config.expected_window)) : 1.0 / config.max_panel_m;
  const double k_hi = guided ? 1.0 / (config.expected_panel_m * (1 - config.expected_window)) : 1.0 / config.min_panel_m;
  for (double k0 = k_lo; k0 <= k_hi; k0 += bin_cpm / 2) {
    double sum = 0;
    int h = 0;
    for (; (h + 1) * k0 <= top; ++h) sum += lr[nearest(lr, (h + 1) * k0 / bin_cpm)];
    if (h == 0) continue;
    const double score = sum / std::sqrt(static_cast<double>(h));
    ++candidates;
    if (score > best_score) {
      best_score = score;
      best_k0 = k0;
    }
  }
  if (candidates < (guided ? 2u : 8u)) return best;
  if (!guided) best_k0 = past_subharmonics(lr, best_k0, top, bin_cpm, config);
  // Significance against the bins' own scatter: without lines a candidate's score is a sum of H
  // centred values over sqrt(H), with the bins' robust standard deviation.
  std::vector<double> band(lr.begin() + band_lo, lr.begin() + band_hi), dev;
  for (double x : band) dev.push_back(std::abs(x));
  const double sigma = 1.4826 * median_of(dev);
  double sum = 0;
  int harmonics = 0;
  for (int h = 1; h * best_k0 <= top; ++h, ++harmonics) sum += lr[nearest(lr, h * best_k0 / bin_cpm)];
  best.significance = sigma > 0 && harmonics > 0 ? sum / std::sqrt(static_cast<double>(harmonics)) / sigma : 0.0;
  if (best.significance < (guided ? config.min_guided_significance : config.min_significance)) return best;
  // Refine through the harmonics that stand out by a third of the best one's log ratio.
  double strongest = 0;
  for (int h = 1; h * best_k0 <= top; ++h) strongest = std::max(strongest, lr[nearest(lr, h * best_k0 / bin_cpm)]);
  double shk = 0, shh = 0;
  for (int h = 1; h * best_k0 <= top; ++h) {
    std::size_t j = nearest(lr, h * best_k0 / bin_cpm);
    if (lr[j] < strongest / 3 || j < 2 || j + 2 >= lr.size()) continue;
    if (raw[j - 1] > raw[j]) --j;
    else if (raw[j + 1] > raw[j]) ++j;
    const double a = raw[j - 1], b = raw[j], c = raw[j + 1];
    const double denom = a - 2 * b + c;
    const double delta = denom < 0 ? std::clamp(0.5 * (a - c) / denom, -0.5, 0.5) : 0.0;
    shk += h * (static_cast<double>(j) + delta) * bin_cpm;
    shh += static_cast<double>(h) * h;
    ++best.harmonics;
  }
  if (best.harmonics == 0) return best;
  best.spatial_cpm = shk / shh;
  best.panel_m = 1.0 / best.spatial_cpm;
  best.found = true;
  return best;
}

void label_joint_harmonics(std::vector<Peak>& peaks, double joint_hz, double bin_hz) {
  if (!(joint_hz > 0)) return;
  for (Peak& p : peaks) {
    const int h = static_cast<int>(std::lround(p.freq / joint_hz));
    if (h >= 1 && std::abs(p.freq - h * joint_hz) <= bin_hz) p.joint_harmonic = h;
  }
}

}  // namespace roadload::spectra
