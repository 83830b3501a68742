#include "roadload/fleet/schema.hpp"

#include <string>

namespace roadload::fleet {
namespace {

// Version 1. Keys are the results' own identities (a VIN or a vehicle hash, a route hash, a
// recording id), never counters, so two databases fed the same drives in any order hold the same
// rows.
std::string version_1(db::Dialect dialect) {
  const std::string geometry = dialect == db::Dialect::postgres ? "geometry(LineString, 4326)" : "TEXT";
  return R"(
CREATE TABLE vehicles (
  vehicle_key TEXT PRIMARY KEY, vin TEXT, name TEXT NOT NULL);
CREATE TABLE routes (
  route_hash TEXT PRIMARY KEY, name TEXT NOT NULL);
CREATE TABLE sections (
  section_key TEXT PRIMARY KEY, route_hash TEXT NOT NULL REFERENCES routes, cell TEXT NOT NULL,
  surface TEXT, direction TEXT, start_m DOUBLE PRECISION, end_m DOUBLE PRECISION,
  start_lat_deg DOUBLE PRECISION, start_lon_deg DOUBLE PRECISION,
  end_lat_deg DOUBLE PRECISION, end_lon_deg DOUBLE PRECISION, geometry )" +
         geometry + R"(,
  UNIQUE (route_hash, cell));
CREATE TABLE drives (
  drive_key TEXT PRIMARY KEY, recording_id TEXT, vehicle_key TEXT NOT NULL REFERENCES vehicles,
  vehicle_hash TEXT, vehicle_source TEXT, route_hash TEXT NOT NULL REFERENCES routes, route TEXT,
  start_utc TEXT, end_utc TEXT, program TEXT, engine_losses TEXT, cda_prior TEXT, torque_scale TEXT,
  crr DOUBLE PRECISION, crr_sigma DOUBLE PRECISION, crr_identified INTEGER,
  mass_kg DOUBLE PRECISION, cda_m2 DOUBLE PRECISION, distance_m DOUBLE PRECISION, fuel_l DOUBLE PRECISION,
  results_hash TEXT NOT NULL, results_dir TEXT);
CREATE TABLE section_results (
  drive_key TEXT NOT NULL REFERENCES drives ON DELETE CASCADE,
  section_key TEXT NOT NULL REFERENCES sections,
  samples INTEGER, crr DOUBLE PRECISION, crr_lo DOUBLE PRECISION, crr_hi DOUBLE PRECISION,
  crr_sigma DOUBLE PRECISION, identified INTEGER, speed_mps DOUBLE PRECISION, rolling_l DOUBLE PRECISION,
  dynamic_l DOUBLE PRECISION, dynamic_l_per_100km DOUBLE PRECISION, damper_power_w DOUBLE PRECISION,
  tire_power_w DOUBLE PRECISION, crr_tire DOUBLE PRECISION, crr_tire_lo DOUBLE PRECISION,
  crr_tire_hi DOUBLE PRECISION, reason TEXT,
  PRIMARY KEY (drive_key, section_key));
CREATE INDEX section_results_by_section ON section_results (section_key);
CREATE INDEX drives_by_vehicle ON drives (vehicle_key);
)";
}

int current_version(db::Database& db) {
  db.script("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  const auto rows = db.query("SELECT MAX(version) FROM schema_version");
  return rows.empty() ? 0 : static_cast<int>(db::number(rows[0][0]).value_or(0));
}

}  // namespace

int migrate(db::Database& db) {
  db::Transaction tx(db);
  // Workers starting together must not create the tables twice: one migrates, the others wait
  // for its transaction and find the version it wrote. SQLite's BEGIN IMMEDIATE does this alone.
  if (db.dialect() == db::Dialect::postgres) {
    db.execute("SELECT pg_advisory_xact_lock(7226348052)");
    db.script("CREATE EXTENSION IF NOT EXISTS postgis");
  }
  const int found = current_version(db);
  if (found > kSchemaVersion) {
    throw db::DatabaseError(db.name() + ": schema version " + std::to_string(found) + " is newer than this roadload's " +
                            std::to_string(kSchemaVersion) + ": upgrade roadload");
  }
  // Each step takes the schema one version up; a step is never edited once released.
  for (int v = found + 1; v <= kSchemaVersion; ++v) {
    if (v == 1) db.script(version_1(db.dialect()));
    db.execute("INSERT INTO schema_version (version) VALUES (?)", {std::int64_t{v}});
  }
  tx.commit();
  return found;
}

}  // namespace roadload::fleet
