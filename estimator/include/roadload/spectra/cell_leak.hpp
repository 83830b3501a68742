#pragma once
// What a cell's average borrowed from the cells beside it. A Welch segment that straddles a
// boundary is shared among the cells by window energy (segment_weights.hpp), so a cell's average
// holds about half a segment of each neighbour: nothing against long cells of alike pavements, but
// a short asphalt cell between faulted concrete ones reads several per cent high. For any power x
// linear in the spectra, with w_c a segment's share in cell c and N_cj = sum over segments of
// w_c w_j, the cell's weighted sum is
//   b_c = sum w_c x_seg = N_cc x_c + sum_j N_cj x_j + N_c,off x_off
// (off: the segment's part on no cell). One Jacobi step, the neighbours' averages standing in for
// x_j and the cell's own for x_off, takes the leak out to first order (CellLeaks::unblur).
#include <array>
#include <cstddef>
#include <vector>

#include "roadload/spectra/segment_weights.hpp"

namespace roadload::spectra {

struct CellLeak {
  static constexpr std::size_t kNeighbours = 8;
  double own = 0;  // N_cc
  double off = 0;  // N_c,off
  std::array<int, kNeighbours> neighbour{};
  std::array<double, kNeighbours> weight{};  // N_cj
  std::size_t count = 0;
  bool overflow = false;  // more neighbours than kept: the average is left as it is
};

class CellLeaks {
 public:
  CellLeaks(std::size_t cells, std::size_t axles) : axles_(axles), leak_(cells * axles) {}
  void add(std::size_t axle, const SegmentShares& shares);
  const CellLeak& leak(std::size_t cell, std::size_t axle) const { return leak_[cell * axles_ + axle]; }

 private:
  std::size_t axles_;
  std::vector<CellLeak> leak_;
};

// x_c from the cell's average `average` over `weight` (sum of its shares) and its neighbours'
// averages, neighbour_average(j) for the j-th neighbour of `k`. A cell whose own segments do not
// carry at least half its weight (shorter than a segment) has no footing: its average is returned.
template <typename NeighbourAverage>
double unblur(const CellLeak& k, double average, double weight, NeighbourAverage&& neighbour_average) {
  if (weight <= 0 || k.overflow || k.own < 0.5 * weight) return average;
  double b = (weight - k.off) * average;
  for (std::size_t j = 0; j < k.count; ++j) b -= k.weight[j] * neighbour_average(j);
  return b / k.own;
}

}  // namespace roadload::spectra
