#pragma once
// Where J1939 definitions come from: the built-in config/j1939-core.dbc, then users' own DBCs.
#include <optional>
#include <string>

#include "roadload/j1939/database.hpp"
#include "roadload/parse_error.hpp"

namespace roadload {

// Where the built-in definitions, routes, scenarios and vehicles are: $ROADLOAD_DATADIR when set;
// else share/roadload beside the running program's bin or sbin folder, when it holds
// j1939-core.dbc (an installed copy, whatever its prefix); else config/ of the source tree the
// program was built from (a program run from its build folder).
std::string data_dir();
// data_dir()/j1939-core.dbc.
std::string core_dbc_path();
std::optional<ParseError> load_dbc_file(j1939::Database& db, const std::string& path);

}  // namespace roadload
