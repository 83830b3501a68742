#pragma once
// DBC reader (the Vector format users already have). Pure: the caller reads the file.
// Messages are keyed by PGN: a DBC's extended identifier carries priority, SA and for PDU1 a
// destination, none of which select the definition.
#include <optional>
#include <string_view>

#include "roadload/j1939/database.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::j1939 {

// Adds the DBC's messages to `db`. On error `db` is left unchanged.
std::optional<ParseError> load_dbc(Database& db, std::string_view text, std::string_view source);

}  // namespace roadload::j1939
