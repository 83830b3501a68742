#pragma once
#include <string>

#include "roadload/fleet/network.hpp"

namespace roadload::fleet {

// network.html: the sections on a map coloured by CRR, each with its interval, drives and trucks
// on hover and in a table. One file, no scripts, fonts or tiles fetched: it opens in an office
// without a network.
std::string network_map(const NetworkView& view);

}  // namespace roadload::fleet
