#pragma once
// Number formatting shared by the network's files: fixed decimals, empty (CSV) or null (JSON)
// for what is not a number.
#include <cmath>
#include <cstdio>
#include <string>

namespace roadload::fleet {

inline std::string csv_number(double v, int decimals) {
  if (!std::isfinite(v)) return "";
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

inline std::string json_number(double v, int decimals) {
  const std::string s = csv_number(v, decimals);
  return s.empty() ? "null" : s;
}

}  // namespace roadload::fleet
