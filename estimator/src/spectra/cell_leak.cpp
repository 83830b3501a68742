#include "roadload/spectra/cell_leak.hpp"

namespace roadload::spectra {

void CellLeaks::add(std::size_t axle, const SegmentShares& shares) {
  double on_cells = 0;
  for (std::size_t i = 0; i < shares.count; ++i) on_cells += shares.share[i].weight;
  const double off = on_cells < 1.0 ? 1.0 - on_cells : 0.0;
  for (std::size_t i = 0; i < shares.count; ++i) {
    const double wi = shares.share[i].weight;
    CellLeak& k = leak_[static_cast<std::size_t>(shares.share[i].cell) * axles_ + axle];
    k.own += wi * wi;
    k.off += wi * off;
    for (std::size_t j = 0; j < shares.count; ++j) {
      if (j == i) continue;
      const int cj = shares.share[j].cell;
      std::size_t slot = 0;
      while (slot < k.count && k.neighbour[slot] != cj) ++slot;
      if (slot == k.count) {
        if (k.count == CellLeak::kNeighbours) {
          k.overflow = true;
          continue;
        }
        k.neighbour[k.count++] = cj;
      }
      k.weight[slot] += wi * shares.share[j].weight;
    }
  }
}

}  // namespace roadload::spectra
