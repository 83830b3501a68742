// The streaming Welch PSD: segment timing, Parseval, the cross-spectrum identity the suspension's
// relative motion relies on, and no heap once built. (Equality with scipy.signal.welch itself is
// tests/cli/psd-matches-scipy.py.)
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "allocation_counter.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::spectra {
namespace {

std::vector<double> density(const WelchPsd& p) {
  std::vector<double> d(p.bins());
  p.density(d);
  return d;
}

TEST(WelchPsd, SegmentsStartEveryHopOnceTheFirstIsFull) {
  WelchPsd psd({100.0, 64, 48});
  for (int i = 0; i < 63; ++i) psd.push(1.0);
  EXPECT_EQ(psd.segments(), 0.0);
  psd.push(1.0);
  EXPECT_EQ(psd.segments(), 1.0);
  for (int i = 0; i < 16 * 3; ++i) psd.push(1.0);
  EXPECT_EQ(psd.segments(), 4.0);  // scipy: (n - noverlap) // hop = (112 - 48) // 16
}

TEST(WelchPsd, IntegralOfTheDensityIsTheVarianceOfWhiteNoise) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 0.7);
  WelchPsd psd({400.0, 256, 128});
  for (int i = 0; i < 200000; ++i) psd.push(n(rng) + 9.81);
  const auto d = density(psd);
  double variance = 0;
  for (double x : d) variance += x * bin_hz({400.0, 256, 128});
  EXPECT_NEAR(variance, 0.49, 0.49 * 0.02);  // the mean (1 g) is removed per segment
}

TEST(WelchPsd, ASineCarriesItsMeanSquareInItsLine) {
  const double fs = 200.0, f0 = 12.5, amp = 0.3;  // f0 on a bin: 256 / 200 * 12.5 = 16
  WelchPsd psd({fs, 256, 128});
  for (int i = 0; i < 20000; ++i) psd.push(amp * std::sin(2 * std::numbers::pi * f0 * i / fs));
  const auto d = density(psd);
  double line = 0;
  for (std::size_t k = 14; k <= 18; ++k) line += d[k] * fs / 256;
  EXPECT_NEAR(line, amp * amp / 2, 1e-9);
}

TEST(SpectralSum, RelativeMotionFromCrossSpectraEqualsTheDifferenceSignal) {
  const WelchConfig c{200.0, 128, 64};
  SegmentTransform tr(c);
  SpectralSum saa(bin_count(c)), sbb(bin_count(c)), sab(bin_count(c)), sdiff(bin_count(c));
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> a(128), b(128), d(128);
  std::vector<std::complex<double>> xa(bin_count(c)), xb(bin_count(c)), xd(bin_count(c));
  for (int seg = 0; seg < 20; ++seg) {
    for (std::size_t i = 0; i < 128; ++i) {
      a[i] = n(rng);
      b[i] = 0.6 * a[i] + 0.4 * n(rng);
      d[i] = a[i] - b[i];
    }
    tr.transform(a, xa);
    tr.transform(b, xb);
    tr.transform(d, xd);
    saa.add(xa);
    sbb.add(xb);
    sab.add(xa, xb);
    sdiff.add(xd);
  }
  std::vector<std::complex<double>> paa(bin_count(c)), pbb(bin_count(c)), pab(bin_count(c)), pd(bin_count(c));
  saa.density(tr.density_scale(), paa);
  sbb.density(tr.density_scale(), pbb);
  sab.density(tr.density_scale(), pab);
  sdiff.density(tr.density_scale(), pd);
  for (std::size_t k = 0; k < bin_count(c); ++k) {
    const double rel = paa[k].real() + pbb[k].real() - 2 * pab[k].real();
    EXPECT_NEAR(rel, pd[k].real(), 1e-12 * (1 + pd[k].real())) << "bin " << k;
  }
}

TEST(WelchPsd, RejectsAnOddSegmentOrAnOverlapAsLongAsTheSegment) {
  EXPECT_TRUE(check({100.0, 63, 10}).has_value());
  EXPECT_TRUE(check({100.0, 64, 64}).has_value());
  EXPECT_TRUE(check({0.0, 64, 32}).has_value());
  EXPECT_FALSE(check({100.0, 64, 32}).has_value());
  EXPECT_THROW(WelchPsd({100.0, 63, 10}), std::invalid_argument);
}

TEST(WelchPsd, PushAndTransformDoNotAllocate) {
  WelchPsd psd({4000.0, 4096, 2048});
  std::size_t allocations = 0;
  {
    test::CountAllocations count;
    for (int i = 0; i < 20000; ++i) psd.push(std::sin(0.01 * i));
    allocations = count.count();
  }
  EXPECT_EQ(psd.segments(), 8.0);
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace roadload::spectra
