#pragma once
// The report's sim-to-real section, from RESULTS/gap.json (`roadload gap --json`) and
// RESULTS/gap-tables.json (`roadload gap tables --json`), whichever are there.
#include <string>

#include "roadload/results/json.hpp"

namespace roadload::report {

std::string gap_section(const results::JsonValue* gap, const results::JsonValue* tables);

}  // namespace roadload::report
