#pragma once
// Forward FFT of a real sequence of one fixed, even length: bins 0 .. n/2.
//
// Eigen's FFT module (kissfft inside, MPL-2) in double precision: docs/spectra.md gives the
// choice and its measurements. Plans and scratch are made in the constructor, so transform()
// never allocates.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>

namespace roadload::spectra {

class RealFft {
 public:
  explicit RealFft(std::size_t n);  // n even, >= 2
  ~RealFft();
  RealFft(RealFft&&) noexcept;
  RealFft& operator=(RealFft&&) noexcept;

  std::size_t size() const { return n_; }
  std::size_t bins() const { return n_ / 2 + 1; }
  // in.size() == size(), out.size() == bins(); unscaled: X_k = sum_n x_n e^{-2 pi i k n / N}.
  void forward(std::span<const double> in, std::span<std::complex<double>> out);

 private:
  struct Impl;
  std::size_t n_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadload::spectra
