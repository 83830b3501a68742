#pragma once
// Effects no feature of the diagnosis can see. A fit of one would only fit the noise, and could be
// named for a drive that lacks it, so the library simulates no response for them and the
// diagnosis says why it leaves them out.
#include <vector>

#include "roadload/sim/effects.hpp"

namespace roadload::gap {

// Why the features cannot see the effect; nullptr for one they can.
const char* unseen_by_features(sim::Effect e);

// The effects the library simulates a response for, in the catalog's order.
std::vector<sim::Effect> fitted_effects();

}  // namespace roadload::gap
