#pragma once
// An engine-loss table as `roadload calibrate` writes it (rpm,loss_nm,sigma_nm,friction_nm,
// eec3_loss_nm,eec3_friction_nm,hold_s,samples; one line per steady hold; friction_nm empty where
// the calibration could not separate it), read back for `roadload analyze --engine-losses`.
#include <optional>
#include <string>
#include <vector>

#include "roadload/engine_loss_calibration.hpp"
#include "roadload/parse_error.hpp"

namespace roadload {

Parsed<model::EngineLossMap> load_engine_loss_file(const std::string& path);
std::optional<ParseError> write_engine_loss_file(const std::string& path, const std::vector<EngineLossHold>& holds);

}  // namespace roadload
