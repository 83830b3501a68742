#pragma once
// Welch's power spectral density, streaming, exactly as
//
//     scipy.signal.welch(x, fs, window="hann", nperseg=N, noverlap=M, detrend="constant",
//                        return_onesided=True, scaling="density", average="mean")
//
// computes it (and scipy.signal.csd for cross-spectra): segments of N samples every N - M samples
// from the first, each with its mean removed, multiplied by the periodic Hann window and
// transformed; |X|^2 (or conj(X) Y) averaged over segments, scaled by 1 / (fs sum w^2) and doubled
// in every bin but DC and Nyquist. Densities are per Hz: a signal in m/s^2 gives (m/s^2)^2/Hz.
//
// Storage is sized at construction; push() and transform() never allocate.
#include <complex>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadload/spectra/fft.hpp"

namespace roadload::spectra {

struct WelchConfig {
  double fs_hz = 1.0;
  std::size_t nperseg = 256;   // even
  std::size_t noverlap = 128;  // < nperseg; scipy's default is nperseg / 2
};

// Why the configuration cannot be used, or nothing.
std::optional<std::string> check(const WelchConfig& c);
inline std::size_t bin_count(const WelchConfig& c) { return c.nperseg / 2 + 1; }
inline double bin_hz(const WelchConfig& c) { return c.fs_hz / static_cast<double>(c.nperseg); }
inline std::size_t hop(const WelchConfig& c) { return c.nperseg - c.noverlap; }

// The periodic Hann window (scipy.signal.get_window("hann", n)).
std::vector<double> hann_periodic(std::size_t n);

// One segment: mean removed, windowed, transformed.
class SegmentTransform {
 public:
  explicit SegmentTransform(const WelchConfig& c);  // throws std::invalid_argument if check(c) fails
  const WelchConfig& config() const { return config_; }
  std::size_t bins() const { return fft_.bins(); }
  // 1 / (fs sum w^2): turns a mean |X|^2 into a two-sided density per Hz.
  double density_scale() const { return density_scale_; }
  // segment.size() == nperseg, bins.size() == bins().
  void transform(std::span<const double> segment, std::span<std::complex<double>> bins);

 private:
  WelchConfig config_;
  std::vector<double> window_, work_;
  RealFft fft_;
  double density_scale_ = 0;
};

// Sum of segment spectra: |X|^2 for an auto-spectrum, conj(X) Y for a cross-spectrum (scipy's csd
// convention). Densities come out one-sided and per Hz.
class SpectralSum {
 public:
  explicit SpectralSum(std::size_t bins) : sum_(bins) {}
  void add(std::span<const std::complex<double>> x);
  void add(std::span<const std::complex<double>> x, std::span<const std::complex<double>> y);
  // Weighted: a segment that counts as `weight` segments (a share of it in this average).
  void add_scaled(std::span<const std::complex<double>> x, std::span<const std::complex<double>> y, double weight);
  void merge(const SpectralSum& other);
  void clear();
  double segments() const { return segments_; }
  std::size_t bins() const { return sum_.size(); }
  // Mean over segments times `density_scale`, doubled except at DC and (even N) Nyquist.
  // out.size() == bins(). Zero everywhere when no segment was added.
  void density(double density_scale, std::span<std::complex<double>> out) const;
  void density(double density_scale, std::span<double> out) const;  // the real part

 private:
  double weight(std::size_t k) const { return (k == 0 || k + 1 == sum_.size()) ? 1.0 : 2.0; }
  std::vector<std::complex<double>> sum_;
  double segments_ = 0;
};

// The last nperseg samples of one stream, and when the next Welch segment is due.
class SegmentRing {
 public:
  explicit SegmentRing(const WelchConfig& c);
  // True when this sample completes a segment (the first at nperseg samples, then every hop).
  bool push(double x);
  // The segment, oldest sample first; out.size() == nperseg.
  void copy_segment(std::span<double> out) const;
  std::size_t samples() const { return total_; }
  void clear();

 private:
  std::vector<double> ring_;
  std::size_t hop_;
  std::size_t next_ = 0;  // where the next sample goes
  std::size_t total_ = 0;
};

// One channel, one average: scipy.signal.welch over everything pushed since the last clear().
class WelchPsd {
 public:
  explicit WelchPsd(const WelchConfig& c);
  void push(double x);
  double segments() const { return sum_.segments(); }
  void density(std::span<double> out) const { sum_.density(transform_.density_scale(), out); }
  std::size_t bins() const { return transform_.bins(); }
  void clear();

 private:
  SegmentTransform transform_;
  SegmentRing ring_;
  SpectralSum sum_;
  std::vector<double> segment_;
  std::vector<std::complex<double>> spectrum_;
};

}  // namespace roadload::spectra
