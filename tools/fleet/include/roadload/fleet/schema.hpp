#pragma once
// The fleet database's tables (docs/fleet.md, "Schema"), the same in SQLite and PostgreSQL but for
// the sections' geometry: a PostGIS LineString there, GeoJSON text in SQLite.
#include "roadload/db/database.hpp"

namespace roadload::fleet {

// The version this program writes. A database of an older one is migrated step by step in one
// transaction; one of a newer program is refused rather than written in a shape it does not know.
inline constexpr int kSchemaVersion = 1;

// Creates or migrates the schema; returns the version found before (0: an empty database).
// Throws db::DatabaseError, naming the database, on a newer schema or a failed step.
int migrate(db::Database& db);

}  // namespace roadload::fleet
