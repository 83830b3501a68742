#pragma once
// The vehicle files config/vehicles ships, for tests and benchmarks: loaded once; one that does not
// load stops the program with its error, which fails whatever asked for it.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "roadload/vehicle.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::shipped {

inline Vehicle load_shipped_vehicle(const std::string& name) {
  // Appended piece by piece: GCC 12 warns (-Warray-bounds) on the inlined chain of + here.
  std::string path = ROADLOAD_CONFIG_DIR;
  path.append("/vehicles/").append(name).append(".toml");
  auto v = load_vehicle_file(path);
  if (!v) {
    std::fprintf(stderr, "%s\n", v.error().to_string().c_str());
    std::abort();
  }
  return v.value();
}

// The seed report's MnROAD truck.
inline const Vehicle& mnroad_vehicle() {
  static const Vehicle v = load_shipped_vehicle("mnroad-truck");
  return v;
}

}  // namespace roadload::shipped
