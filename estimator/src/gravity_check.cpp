#include "roadload/gravity_check.hpp"

#include <cmath>

#include "roadload/model/longitudinal.hpp"

namespace roadload {

std::vector<GravityCheck::Finding> GravityCheck::implausible(std::uint64_t min_samples, double tolerance_mps2) const {
  std::vector<Finding> out;
  for (std::size_t id = 0; id < sums_.size(); ++id) {
    const Sum& s = sums_[id];
    if (s.n < min_samples) continue;
    const double mean = s.z / static_cast<double>(s.n);
    if (std::abs(mean - model::kGravity_mps2) > tolerance_mps2) out.push_back({static_cast<std::uint8_t>(id), mean, s.n});
  }
  return out;
}

}  // namespace roadload
