#include "roadload/residual_scatter.hpp"

#include <algorithm>
#include <cmath>

namespace roadload {

double ResidualScatter::sigma(double swdd) const {
  const double widening = (1.0 + correlation) / (1.0 - correlation);
  return swdd > 0 ? std::sqrt(chi2_per_dof * widening / swdd) : 0.0;
}

ResidualScatter residual_scatter(std::span<const Residual> residuals) {
  ResidualScatter out;
  if (residuals.size() < 2) return out;
  double chi2 = 0, lag1 = 0, previous = 0;
  for (const Residual& r : residuals) {
    chi2 += r.z * r.z;
    lag1 += r.first ? 0.0 : r.z * previous;
    previous = r.z;
  }
  const auto n = static_cast<double>(residuals.size());
  out.chi2_per_dof = chi2 / (n - 1);
  // The lag-one estimate is biased low by (1 + 4 r) / n over n cells (Kendall), put back here.
  const double r = chi2 > 0 ? lag1 / chi2 : 0.0;
  out.correlation = std::clamp(r + (1.0 + 4.0 * r) / n, 0.0, 0.9);
  return out;
}

}  // namespace roadload
