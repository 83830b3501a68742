#include "roadload/pavement_groups.hpp"

#include <cstdio>

namespace roadload {

PavementGroups group_pavements(std::span<const PavementKey> cells) {
  PavementGroups g;
  for (const PavementKey& c : cells) {
    const bool jointed = c.surface == "concrete" && c.joint_spacing_m > 0;
    std::string name = c.surface.empty() ? "unknown" : std::string(c.surface);
    if (jointed) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "-%.2fm", c.joint_spacing_m);
      name += buf;
    }
    std::size_t i = 0;
    while (i < g.names.size() && g.names[i] != name) ++i;
    if (i == g.names.size()) {
      g.names.push_back(name);
      g.panel_m.push_back(jointed ? c.joint_spacing_m : 0.0);
    }
    g.cell_group.push_back(static_cast<int>(i));
  }
  return g;
}

}  // namespace roadload
