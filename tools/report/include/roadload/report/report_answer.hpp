#pragma once
// The top of the report: what a pavement engineer came for, each pavement type's CRR with its
// interval and whether the drive identifies it, and the fuel rolling on it costs; then which
// truck, route, date and calibration the numbers came from (trip.json's "pavements" and
// "provenance", written by `roadload analyze`).
#include <string>

#include "roadload/results/json.hpp"

namespace roadload::report {

std::string answer_section(const results::JsonValue& trip);

}  // namespace roadload::report
