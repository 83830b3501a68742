#include "roadload/gap/unseen.hpp"

namespace roadload::gap {

const char* unseen_by_features(sim::Effect e) {
  switch (e) {
    case sim::Effect::can_accel_offset:
      return "no feature compares accelerometer and CAN timing: a stamp offset only shifts where vibration is binned";
    case sim::Effect::wind_gusts:
    case sim::Effect::drafting:
    case sim::Effect::fan_engagement:
      return "random episodes: the library's realisation does not match the drive's cell by cell, and no feature "
             "summarises the episodes independently of when they happen";
    default: return nullptr;
  }
}

std::vector<sim::Effect> fitted_effects() {
  std::vector<sim::Effect> out;
  for (const auto& e : sim::effect_catalog()) {
    if (unseen_by_features(e.id) == nullptr) out.push_back(e.id);
  }
  return out;
}

}  // namespace roadload::gap
