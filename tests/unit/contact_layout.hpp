#pragma once
// The contact-force tests' truck: the simulator's MnROAD sensor layout (ids 0..7) over the
// shipped vehicle file.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "vehicles.hpp"

namespace roadload::contact_test {

// The simulator's MnROAD layout: sensor ids 0..7.
inline const std::vector<std::pair<std::int64_t, std::string>> kMounts = {
    {0, "tractor-front-axle-left"},   {1, "tractor-front-frame-left"}, {2, "tractor-drive1-axle-left"},
    {3, "tractor-drive1-frame-left"}, {4, "tractor-drive2-axle-left"}, {5, "trailer-axle1-left"},
    {6, "trailer-axle1-frame-left"},  {7, "trailer-axle2-left"},
};

inline std::vector<SensorPlacement> placements(const std::vector<std::pair<std::int64_t, std::string>>& mounts) {
  std::vector<SensorPlacement> out;
  for (const auto& [id, pos] : mounts) out.push_back({id, "accelerometer", pos});
  return out;
}

using shipped::mnroad_vehicle;

inline AxleLayout mnroad_layout() {
  const auto p = placements(kMounts);
  auto l = build_axle_layout(p, mnroad_vehicle());
  EXPECT_TRUE(l.ok()) << (l.ok() ? "" : l.error().to_string());
  return l.value();
}

}  // namespace roadload::contact_test
