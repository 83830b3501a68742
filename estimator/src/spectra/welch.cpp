#include "roadload/spectra/welch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace roadload::spectra {

std::optional<std::string> check(const WelchConfig& c) {
  if (!(c.fs_hz > 0) || !std::isfinite(c.fs_hz)) return "sampling rate must be positive";
  if (c.nperseg < 2 || c.nperseg % 2 != 0) return "segment length must be even and at least 2";
  if (c.noverlap >= c.nperseg) return "overlap must be shorter than the segment";
  return std::nullopt;
}

std::vector<double> hann_periodic(std::size_t n) {
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i)
    w[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n));
  return w;
}

namespace {
const WelchConfig& checked(const WelchConfig& c) {
  if (auto why = check(c)) throw std::invalid_argument("Welch configuration: " + *why);
  return c;
}
}  // namespace

SegmentTransform::SegmentTransform(const WelchConfig& c)
    : config_(checked(c)), window_(hann_periodic(c.nperseg)), work_(c.nperseg), fft_(c.nperseg) {
  double sum_w2 = 0;
  for (double w : window_) sum_w2 += w * w;
  density_scale_ = 1.0 / (c.fs_hz * sum_w2);
}

void SegmentTransform::transform(std::span<const double> segment, std::span<std::complex<double>> bins) {
  double mean = 0;
  for (double x : segment) mean += x;
  mean /= static_cast<double>(segment.size());
  for (std::size_t i = 0; i < work_.size(); ++i) work_[i] = (segment[i] - mean) * window_[i];
  fft_.forward(work_, bins);
}

void SpectralSum::add(std::span<const std::complex<double>> x) {
  for (std::size_t k = 0; k < sum_.size(); ++k) sum_[k] += std::norm(x[k]);
  segments_ += 1;
}

void SpectralSum::add(std::span<const std::complex<double>> x, std::span<const std::complex<double>> y) { add_scaled(x, y, 1.0); }

void SpectralSum::add_scaled(std::span<const std::complex<double>> x, std::span<const std::complex<double>> y, double weight) {
  // Spelled out in reals: std::complex's product checks for NaN and defeats vectorisation.
  for (std::size_t k = 0; k < sum_.size(); ++k) {
    const double a = weight * x[k].real(), b = weight * x[k].imag(), yr = y[k].real(), yi = y[k].imag();
    sum_[k] += std::complex<double>(a * yr + b * yi, a * yi - b * yr);
  }
  segments_ += weight;
}

void SpectralSum::merge(const SpectralSum& other) {
  for (std::size_t k = 0; k < sum_.size(); ++k) sum_[k] += other.sum_[k];
  segments_ += other.segments_;
}

void SpectralSum::clear() {
  for (auto& s : sum_) s = 0;
  segments_ = 0;
}

void SpectralSum::density(double density_scale, std::span<std::complex<double>> out) const {
  const double per = segments_ > 0 ? density_scale / segments_ : 0.0;
  for (std::size_t k = 0; k < sum_.size(); ++k) out[k] = sum_[k] * (per * weight(k));
}

void SpectralSum::density(double density_scale, std::span<double> out) const {
  const double per = segments_ > 0 ? density_scale / segments_ : 0.0;
  for (std::size_t k = 0; k < sum_.size(); ++k) out[k] = sum_[k].real() * (per * weight(k));
}

SegmentRing::SegmentRing(const WelchConfig& c) : ring_(checked(c).nperseg), hop_(hop(c)) {}

bool SegmentRing::push(double x) {
  ring_[next_] = x;
  next_ = next_ + 1 == ring_.size() ? 0 : next_ + 1;
  ++total_;
  return total_ >= ring_.size() && (total_ - ring_.size()) % hop_ == 0;
}

void SegmentRing::copy_segment(std::span<double> out) const {
  // next_ is the oldest sample once the ring is full: the tail of the ring, then its head.
  const auto tail = ring_.begin() + static_cast<std::ptrdiff_t>(next_);
  const auto rest = std::copy(tail, ring_.end(), out.begin());
  std::copy(ring_.begin(), tail, rest);
}

void SegmentRing::clear() {
  next_ = 0;
  total_ = 0;
}

WelchPsd::WelchPsd(const WelchConfig& c)
    : transform_(c), ring_(c), sum_(bin_count(c)), segment_(c.nperseg), spectrum_(bin_count(c)) {}

void WelchPsd::push(double x) {
  if (!ring_.push(x)) return;
  ring_.copy_segment(segment_);
  transform_.transform(segment_, spectrum_);
  sum_.add(spectrum_);
}

void WelchPsd::clear() {
  ring_.clear();
  sum_.clear();
}

}  // namespace roadload::spectra
