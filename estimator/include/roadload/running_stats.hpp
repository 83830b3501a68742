#pragma once
// Count, mean and sample standard deviation in one pass (Welford's update): stable where the
// naive sum of squares cancels (contact forces: a 2 kN ripple on 75 kN).
#include <cmath>
#include <cstdint>

namespace roadload {

struct RunningStats {
  std::uint64_t n = 0;
  double mean = 0, m2 = 0;

  void add(double x) {
    ++n;
    const double d = x - mean;
    mean += d / static_cast<double>(n);
    m2 += d * (x - mean);
  }
  double std() const { return n > 1 ? std::sqrt(m2 / static_cast<double>(n - 1)) : 0.0; }
};

}  // namespace roadload
