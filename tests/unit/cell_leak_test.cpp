// A short cell between two of three times its power: segments straddling its ends lift its plain
// average by several per cent; the leak taken out gives it back.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "roadload/spectra/cell_leak.hpp"

namespace roadload::spectra {
namespace {

constexpr double kSampleS = 0.01;
constexpr std::size_t kSegment = 128;  // 1.28 s
constexpr std::size_t kHop = 32;

// Cells [2, 20) s, [20, 26) s and [26, 44) s; before 2 s the segment is on no cell.
int cell_at(double t) { return t < 2 ? -1 : t < 20 ? 0 : t < 26 ? 1 : t < 44 ? 2 : -1; }

struct Blurred {
  std::array<double, 3> sum{}, weight{};
  double average(std::size_t c) const { return sum[c] / weight[c]; }
};

// Each segment's shares by Hann^2 energy, its power the shares' mix of the cells' true powers.
Blurred run(const std::array<double, 3>& truth, CellLeaks& leaks) {
  std::vector<double> w2(kSegment);
  double total = 0;
  for (std::size_t j = 0; j < kSegment; ++j) {
    const double h = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(kSegment));
    total += w2[j] = h * h;
  }
  Blurred b;
  for (std::size_t start = 0; static_cast<double>(start + kSegment) * kSampleS < 44.0; start += kHop) {
    SegmentShares s;
    for (std::size_t j = 0; j < kSegment; ++j) {
      const int c = cell_at(static_cast<double>(start + j) * kSampleS);
      if (c < 0) continue;
      std::size_t i = 0;
      while (i < s.count && s.share[i].cell != c) ++i;
      if (i == s.count) s.share[s.count++] = {c, 0.0};
      s.share[i].weight += w2[j] / total;
    }
    double on = 0, power = 0;
    for (std::size_t i = 0; i < s.count; ++i) {
      on += s.share[i].weight;
      power += s.share[i].weight * truth[static_cast<std::size_t>(s.share[i].cell)];
    }
    // The stretch before the first cell is as loud as the first cell.
    power += (1.0 - on) * truth[0];
    for (std::size_t i = 0; i < s.count; ++i) {
      const auto c = static_cast<std::size_t>(s.share[i].cell);
      b.sum[c] += s.share[i].weight * power;
      b.weight[c] += s.share[i].weight;
    }
    leaks.add(0, s);
  }
  return b;
}

TEST(CellLeak, AShortQuietCellBetweenLoudOnesIsGivenBackItsOwnPower) {
  const std::array<double, 3> truth = {300.0, 100.0, 300.0};
  CellLeaks leaks(3, 1);
  const Blurred b = run(truth, leaks);
  EXPECT_GT(b.average(1), 1.05 * truth[1]) << "the plain average should show the leak this test is about";
  for (std::size_t c = 0; c < 3; ++c) {
    const CellLeak& k = leaks.leak(c, 0);
    const double x = unblur(k, b.average(c), b.weight[c],
                            [&](std::size_t j) { return b.average(static_cast<std::size_t>(k.neighbour[j])); });
    EXPECT_NEAR(x, truth[c], 0.01 * truth[c]) << "cell " << c;
  }
}

TEST(CellLeak, ACellShorterThanASegmentKeepsItsAverage) {
  CellLeak k;
  k.own = 0.3;
  k.count = 1;
  k.neighbour[0] = 1;
  k.weight[0] = 0.7;
  EXPECT_EQ(unblur(k, 42.0, 1.0, [](std::size_t) { return 1000.0; }), 42.0);
}

}  // namespace
}  // namespace roadload::spectra
