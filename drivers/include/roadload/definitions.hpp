#pragma once
// Where J1939 definitions come from: the built-in config/j1939-core.dbc, then users' own DBCs.
#include <optional>
#include <string>

#include "roadload/j1939/database.hpp"
#include "roadload/parse_error.hpp"

namespace roadload {

// $ROADLOAD_DATADIR when set, else the data directory fixed at build time (config/ of the source).
std::string data_dir();
// data_dir()/j1939-core.dbc.
std::string core_dbc_path();
std::optional<ParseError> load_dbc_file(j1939::Database& db, const std::string& path);

}  // namespace roadload
