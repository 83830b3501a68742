#include "roadload/network/minimize.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace roadload::network {
namespace {

using Point = std::vector<double>;

Point along(const Point& from, const Point& to, double t) {
  Point p(from.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = from[i] + t * (to[i] - from[i]);
  return p;
}

}  // namespace

Minimum minimize(const std::function<double(const std::vector<double>&)>& f, std::vector<double> start, double step, double tolerance,
                 int max_evaluations) {
  const std::size_t n = start.size();
  std::vector<Point> simplex(n + 1, start);
  for (std::size_t i = 0; i < n; ++i) simplex[i + 1][i] += step;
  std::vector<double> value(n + 1);
  int evaluations = 0;
  const auto eval = [&](const Point& p) {
    ++evaluations;
    const double v = f(p);
    return std::isfinite(v) ? v : HUGE_VAL;
  };
  for (std::size_t i = 0; i <= n; ++i) value[i] = eval(simplex[i]);
  std::vector<std::size_t> order(n + 1);
  bool converged = false;
  while (evaluations < max_evaluations) {
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return value[a] < value[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
    if (std::abs(value[worst] - value[best]) <= tolerance * (1 + std::abs(value[best]))) {
      converged = true;
      break;
    }
    Point centroid(n, 0.0);
    for (std::size_t i : order) {
      if (i == worst) continue;
      for (std::size_t k = 0; k < n; ++k) centroid[k] += simplex[i][k] / static_cast<double>(n);
    }
    const Point reflected = along(centroid, simplex[worst], -1.0);
    const double fr = eval(reflected);
    if (fr < value[best]) {
      const Point expanded = along(centroid, simplex[worst], -2.0);
      const double fe = eval(expanded);
      simplex[worst] = fe < fr ? expanded : reflected;
      value[worst] = std::min(fe, fr);
    } else if (fr < value[second]) {
      simplex[worst] = reflected;
      value[worst] = fr;
    } else {
      const bool outside = fr < value[worst];
      const Point contracted = along(centroid, outside ? reflected : simplex[worst], 0.5);
      const double fc = eval(contracted);
      if (fc < std::min(fr, value[worst])) {
        simplex[worst] = contracted;
        value[worst] = fc;
      } else {
        for (std::size_t i : order) {
          if (i == best) continue;
          simplex[i] = along(simplex[best], simplex[i], 0.5);
          value[i] = eval(simplex[i]);
        }
      }
    }
  }
  const auto best = static_cast<std::size_t>(std::min_element(value.begin(), value.end()) - value.begin());
  return {simplex[best], value[best], evaluations, converged};
}

}  // namespace roadload::network
