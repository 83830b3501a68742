#include "roadload/model/road_roughness.hpp"

#include <cmath>
#include <numbers>

namespace roadload::model {

namespace {
constexpr double kN0_cycles_per_m = 0.1;
constexpr double kIriPerSqrtGd = 0.543;  // m/km per sqrt(G_d(n0) / 1e-6 m^3)
}  // namespace

double iso8608_gd_m3(double iri_m_per_km) {
  const double r = iri_m_per_km / kIriPerSqrtGd;
  return r * r * 1e-6;
}

double roughness_height_sigma_m(double iri_m_per_km, double correlation_m) {
  return std::numbers::pi * kN0_cycles_per_m * std::sqrt(correlation_m * iso8608_gd_m3(iri_m_per_km));
}

RoughnessRipple roughness_ripple(std::span<const AxleWeight> axles, double mass_kg, double height_sigma_m, double correlation_m,
                                 double step_m) {
  if (!(mass_kg > 0) || !(correlation_m > 0) || !(step_m > 0)) return {};
  const auto c = [&](double d) { return std::exp(-std::abs(d) / correlation_m); };
  double level = 0, change = 0;
  for (const AxleWeight& a : axles) {
    for (const AxleWeight& b : axles) {
      const double d = a.behind_front_m - b.behind_front_m;
      level += a.weight_n * b.weight_n * c(d);
      change += a.weight_n * b.weight_n * (2 * c(d) - c(d - step_m) - c(d + step_m));
    }
  }
  if (!(level > 0)) return {};
  const double scale = height_sigma_m / mass_kg;
  // 2 s^2 (1 - exp(-step / L')) = the sum's change: L' from it.
  const double kept = 1.0 - change / (2.0 * level);
  const double lumped_m = kept > 0 && kept < 1 ? -step_m / std::log(kept) : correlation_m;
  return {std::sqrt(level) * scale, lumped_m};
}

}  // namespace roadload::model
