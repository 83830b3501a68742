#include "roadload/sim/iri.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace roadload::sim {
namespace {

constexpr double kIriPerSqrtGd = 0.543;  // m/km per sqrt(1e-6 m^3)
constexpr double kGolden_k1 = 653.0, kGolden_k2 = 63.3, kGolden_mu = 0.15, kGolden_c = 6.0;
constexpr double kIriSpeed_mps = 80.0 / 3.6;
constexpr double kIriBase_m = 0.25;
constexpr double kIriInitLength_m = 11.0;

// The Golden Car plus its input as one 5x5 system [A B; 0 0]: the exponential of it times dt holds
// the exact one-step transition (upper left) and the response to a slope held over the step
// (upper right), without inverting A.
using Mat5 = std::array<std::array<double, 5>, 5>;

Mat5 multiply(const Mat5& a, const Mat5& b) {
  Mat5 out{};
  for (std::size_t i = 0; i < 5; ++i)
    for (std::size_t k = 0; k < 5; ++k)
      for (std::size_t j = 0; j < 5; ++j) out[i][j] += a[i][k] * b[k][j];
  return out;
}

// Scaling and squaring: with |m| <= 1/2 after scaling, 18 Taylor terms reach double precision.
Mat5 expm(Mat5 m) {
  double norm = 0.0;
  for (const auto& row : m) {
    double sum = 0.0;
    for (double v : row) sum += std::abs(v);
    norm = std::max(norm, sum);
  }
  int squarings = 0;
  for (; norm > 0.5; norm *= 0.5) ++squarings;
  for (auto& row : m)
    for (double& v : row) v = std::ldexp(v, -squarings);
  Mat5 result{}, term{};
  for (std::size_t i = 0; i < 5; ++i) result[i][i] = term[i][i] = 1.0;
  for (int k = 1; k <= 18; ++k) {
    term = multiply(term, m);
    for (auto& row : term)
      for (double& v : row) v /= k;
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t j = 0; j < 5; ++j) result[i][j] += term[i][j];
  }
  for (int s = 0; s < squarings; ++s) result = multiply(result, result);
  return result;
}

// State (z_s, z_s', z_u, z_u') driven by the profile slope, so z_s' - z_u' is the suspension
// stroke rate divided by the speed: dimensionless, summed into m/m.
Mat5 golden_car_step(double dt_s) {
  Mat5 m{};
  m[0][1] = 1.0;
  m[1][0] = -kGolden_k2;
  m[1][1] = -kGolden_c;
  m[1][2] = kGolden_k2;
  m[1][3] = kGolden_c;
  m[2][3] = 1.0;
  m[3][0] = kGolden_k2 / kGolden_mu;
  m[3][1] = kGolden_c / kGolden_mu;
  m[3][2] = -(kGolden_k1 + kGolden_k2) / kGolden_mu;
  m[3][3] = -kGolden_c / kGolden_mu;
  m[3][4] = kGolden_k1 / kGolden_mu;
  for (auto& row : m)
    for (double& v : row) v *= dt_s;
  return expm(m);
}

std::size_t nearest_sample(const RoadProfile& profile, double x_m) {
  const double last = static_cast<double>(profile.raw_samples().size() - 1);
  return static_cast<std::size_t>(std::clamp(std::round((x_m - profile.start_m()) / profile.dx_m()), 0.0, last));
}

}  // namespace

double gd_from_iri_m3(double iri_m_per_km) {
  const double r = iri_m_per_km / kIriPerSqrtGd;
  return r * r * 1e-6;
}

double iri_from_gd_m_per_km(double gd_n0_m3) { return kIriPerSqrtGd * std::sqrt(gd_n0_m3 / 1e-6); }

double iri_m_per_km(const RoadProfile& profile, double from_m, double to_m) {
  const std::span<const double> y = profile.raw_samples();
  const double dx_m = profile.dx_m();
  const std::size_t first = nearest_sample(profile, from_m);
  const std::size_t last = nearest_sample(profile, to_m);
  // The 250 mm moving average enters as the slope across one base length (E1926: at least a sample).
  const auto base = static_cast<std::size_t>(std::max(1.0, std::round(kIriBase_m / dx_m)));
  const double base_m = static_cast<double>(base) * dx_m;
  if (last < first + base) return std::numeric_limits<double>::quiet_NaN();

  const Mat5 step = golden_car_step(dx_m / kIriSpeed_mps);
  const auto init_samples = static_cast<std::size_t>(std::round(kIriInitLength_m / dx_m));
  const std::size_t init_end = std::min(last, first + init_samples);
  const double init_slope = init_end > first ? (y[init_end] - y[first]) / (static_cast<double>(init_end - first) * dx_m) : 0.0;
  std::array<double, 4> z{init_slope, 0.0, init_slope, 0.0};
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = first; i + base <= last; ++i, ++count) {
    const double slope = (y[i + base] - y[i]) / base_m;
    std::array<double, 4> next{};
    for (std::size_t r = 0; r < 4; ++r) {
      next[r] = step[r][4] * slope;
      for (std::size_t c = 0; c < 4; ++c) next[r] += step[r][c] * z[c];
    }
    z = next;
    sum += std::abs(z[0] - z[2]);
  }
  return 1000.0 * sum / static_cast<double>(count);
}

}  // namespace roadload::sim
