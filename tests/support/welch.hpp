#pragma once
// A plain Welch PSD for checking the plant's spectra in tests: Hann window, 50 % overlap, mean
// removed per segment, one-sided density (units^2 per Hz, or per cycle/m for a spatial signal).
// Deliberately simple and separate from the estimator's streaming PSD, so a test of the plant
// does not lean on the code it will later check.
#include <cmath>
#include <complex>
#include <numbers>
#include <span>
#include <vector>

#include <unsupported/Eigen/FFT>

namespace roadload::test {

struct Psd {
  std::vector<double> freq;
  std::vector<double> density;
  double at(double f) const {
    const double df = freq[1] - freq[0];
    const auto i = static_cast<std::size_t>(std::lround(f / df));
    return density[i];
  }
};

inline Psd welch(std::span<const double> x, double fs, std::size_t nperseg) {
  std::vector<double> w(nperseg);
  double wss = 0.0;
  for (std::size_t i = 0; i < nperseg; ++i) {
    w[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(nperseg));
    wss += w[i] * w[i];
  }
  Psd out;
  const std::size_t nf = nperseg / 2 + 1;
  out.freq.resize(nf);
  out.density.assign(nf, 0.0);
  for (std::size_t k = 0; k < nf; ++k) out.freq[k] = static_cast<double>(k) * fs / static_cast<double>(nperseg);
  Eigen::FFT<double> fft;
  std::vector<double> seg(nperseg);
  std::vector<std::complex<double>> spec;
  std::size_t count = 0;
  for (std::size_t start = 0; start + nperseg <= x.size(); start += nperseg / 2, ++count) {
    double mean = 0.0;
    for (std::size_t i = 0; i < nperseg; ++i) mean += x[start + i];
    mean /= static_cast<double>(nperseg);
    for (std::size_t i = 0; i < nperseg; ++i) seg[i] = (x[start + i] - mean) * w[i];
    fft.fwd(spec, seg);
    for (std::size_t k = 0; k < nf; ++k) {
      const double scale = (k == 0 || (nperseg % 2 == 0 && k == nf - 1)) ? 1.0 : 2.0;
      out.density[k] += scale * std::norm(spec[k]) / (fs * wss);
    }
  }
  for (auto& d : out.density) d /= static_cast<double>(count);
  return out;
}

}  // namespace roadload::test
