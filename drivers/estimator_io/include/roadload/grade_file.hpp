#pragma once
// A grade profile file as `roadload grade` writes it (s_m,elevation_m,elevation_sigma_m,grade_pct,
// grade_sigma_pct,passes), read back for `roadload analyze --grade`. Empty fields are NaN: a bin
// without a grade stays without one.
#include <optional>
#include <string>

#include "roadload/grade_profile.hpp"
#include "roadload/parse_error.hpp"

namespace roadload {

Parsed<GradeProfile> load_grade_file(const std::string& path, double route_length_m);
// The profile as `roadload grade` writes it: s_m,elevation_m,elevation_sigma_m,grade_pct,grade_sigma_pct,passes.
std::optional<ParseError> write_grade_file(const std::string& path, const GradeProfile& profile);

}  // namespace roadload
