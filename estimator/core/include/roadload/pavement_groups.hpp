#pragma once
// Cells grouped by pavement for the spectra: surface and, on jointed concrete, the inventory's
// panel length ("bituminous", "concrete-4.57m"). The report compares pavements this way (Tables
// 6.5-6.6); a joint line is sought per panel length.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace roadload {

struct PavementKey {
  std::string_view surface;    // "concrete", "bituminous", or empty when unknown
  double joint_spacing_m = 0;  // 0 where the inventory gives none
};

struct PavementGroups {
  std::vector<std::string> names;
  std::vector<double> panel_m;  // per group; 0 where the inventory gives none
  std::vector<int> cell_group;  // per cell
};

PavementGroups group_pavements(std::span<const PavementKey> cells);

}  // namespace roadload
