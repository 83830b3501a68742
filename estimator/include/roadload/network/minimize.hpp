#pragma once
// Nelder-Mead's downhill simplex: a handful of variance parameters, a smooth objective whose
// gradient nobody wrote down. Bounded by its evaluations, never by a clock.
#include <functional>
#include <vector>

namespace roadload::network {

struct Minimum {
  std::vector<double> x;
  double value = 0;
  int evaluations = 0;
  bool converged = false;  // the simplex's values agree within the tolerance
};

Minimum minimize(const std::function<double(const std::vector<double>&)>& f, std::vector<double> start, double step,
                 double tolerance = 1e-9, int max_evaluations = 4000);

}  // namespace roadload::network
