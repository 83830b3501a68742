#include "roadload/spectra/fft.hpp"

#include <stdexcept>
#include <vector>

#include <unsupported/Eigen/FFT>

namespace roadload::spectra {

struct RealFft::Impl {
  Eigen::FFT<double> fft;
};

RealFft::RealFft(std::size_t n) : n_(n), impl_(std::make_unique<Impl>()) {
  if (n < 2 || n % 2 != 0) throw std::invalid_argument("RealFft: length must be even and at least 2");
  impl_->fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  impl_->fft.SetFlag(Eigen::FFT<double>::Unscaled);
  // One transform now builds the plans and sizes kissfft's scratch, so later ones do not allocate.
  const std::vector<double> zeros(n, 0.0);
  std::vector<std::complex<double>> out(bins());
  impl_->fft.fwd(out.data(), zeros.data(), static_cast<Eigen::Index>(n));
}

RealFft::~RealFft() = default;
RealFft::RealFft(RealFft&&) noexcept = default;
RealFft& RealFft::operator=(RealFft&&) noexcept = default;

void RealFft::forward(std::span<const double> in, std::span<std::complex<double>> out) {
  impl_->fft.fwd(out.data(), in.data(), static_cast<Eigen::Index>(n_));
}

}  // namespace roadload::spectra
