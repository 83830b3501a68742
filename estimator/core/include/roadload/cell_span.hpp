#pragma once
// A pavement cell as the estimator takes it: where it lies along the route and how rough it is.
#include <limits>
#include <string>

namespace roadload {

struct CellSpan {
  std::string id;
  double start_m = 0, end_m = 0;
  double iri_m_per_km = std::numeric_limits<double>::quiet_NaN();  // measured; NaN: the analyzer's default
};

}  // namespace roadload
