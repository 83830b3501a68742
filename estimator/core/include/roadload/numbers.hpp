#pragma once
// Constants every layer's arithmetic shares.
#include <limits>

namespace roadload {

// A value not known: a cell without samples, a figure that cannot be formed.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The standard normal's two-sided 90 % quantile: every interval roadload reports is 90 %.
inline constexpr double kZ90 = 1.6448536269514722;

}  // namespace roadload
