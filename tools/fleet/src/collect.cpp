#include "roadload/fleet/collect.hpp"

#include "drive_record.hpp"
#include "roadload/fleet/schema.hpp"

namespace roadload::fleet {
namespace {

// A section's line: its two ends, as PostGIS builds it or as GeoJSON text in SQLite.
std::string section_insert(db::Dialect dialect) {
  const std::string geometry =
      dialect == db::Dialect::postgres
          ? "ST_SetSRID(ST_MakeLine(ST_MakePoint(CAST(? AS DOUBLE PRECISION), CAST(? AS DOUBLE PRECISION)), "
            "ST_MakePoint(CAST(? AS DOUBLE PRECISION), CAST(? AS DOUBLE PRECISION))), 4326)"
          : "'{\"type\":\"LineString\",\"coordinates\":[[' || ? || ',' || ? || '],[' || ? || ',' || ? || ']]}'";
  return "INSERT INTO sections (section_key, route_hash, cell, surface, direction, start_m, end_m, start_lat_deg, "
         "start_lon_deg, end_lat_deg, end_lon_deg, geometry) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, " +
         geometry + ") ON CONFLICT (section_key) DO NOTHING";
}

db::Value text_or_null(const std::string& s) { return s.empty() ? db::Value() : db::Value(s); }

// The truck and the road a drive's rows point at, when they are new.
void insert_owners(db::Database& db, const DriveRecord& d) {
  db.execute("INSERT INTO vehicles (vehicle_key, vin, name) VALUES (?, ?, ?) ON CONFLICT (vehicle_key) DO NOTHING",
             {d.vehicle_key, text_or_null(d.vin), d.vehicle_name});
  db.execute("INSERT INTO routes (route_hash, name) VALUES (?, ?) ON CONFLICT (route_hash) DO NOTHING",
             {d.route_hash, d.route_name.empty() ? d.route : d.route_name});
}

int insert_sections(db::Database& db, const DriveRecord& d) {
  int added = 0;
  const std::string insert = section_insert(db.dialect());
  for (const SectionRecord& s : d.sections) {
    if (!db.query("SELECT 1 FROM sections WHERE section_key = ?", {s.key}).empty()) continue;
    const db::Row ends = s.placed ? db::Row{s.start_lat, s.start_lon, s.end_lat, s.end_lon} : db::Row(4);
    db.execute(insert, {s.key, d.route_hash, s.cell, text_or_null(s.surface), text_or_null(s.direction), s.start_m, s.end_m, ends[0],
                        ends[1], ends[2], ends[3], ends[1], ends[0], ends[3], ends[2]});
    ++added;
  }
  return added;
}

void insert_drive(db::Database& db, const DriveRecord& d) {
  db.execute(
      "INSERT INTO drives (drive_key, recording_id, vehicle_key, vehicle_hash, vehicle_source, route_hash, route, start_utc, "
      "end_utc, program, engine_losses, cda_prior, torque_scale, crr, crr_sigma, crr_identified, mass_kg, cda_m2, distance_m, "
      "fuel_l, results_hash, results_dir) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
      {d.drive_key,
       text_or_null(d.recording_id),
       d.vehicle_key,
       d.vehicle_hash,
       text_or_null(d.vehicle_source),
       d.route_hash,
       text_or_null(d.route),
       text_or_null(d.start_utc),
       text_or_null(d.end_utc),
       text_or_null(d.program),
       text_or_null(d.engine_losses),
       text_or_null(d.cda_prior),
       text_or_null(d.torque_scale),
       d.crr,
       d.crr_sigma,
       d.crr_identified,
       d.mass_kg,
       d.cda_m2,
       d.distance_m,
       d.fuel_l,
       d.results_hash,
       d.dir});
}

void insert_results(db::Database& db, const DriveRecord& d) {
  std::string sql = "INSERT INTO section_results (drive_key, section_key";
  std::string marks = "?, ?";
  for (std::size_t c = 0; c < kResultColumnCount; ++c) {
    sql += std::string(", ") + kResultColumns[c];
    marks += ", ?";
  }
  sql += ") VALUES (" + marks + ")";
  for (std::size_t i = 0; i < d.results.size(); ++i) {
    db::Row row{d.drive_key, d.sections[i].key};
    row.insert(row.end(), d.results[i].begin(), d.results[i].end());
    db.execute(sql, row);
  }
}

}  // namespace

CollectSummary collect(const std::vector<std::string>& result_dirs, const std::string& db_url,
                       const std::function<void(std::size_t)>& progress) {
  CollectSummary sum;
  const auto db = db::open_database(db_url);
  sum.schema_from = migrate(*db);
  for (std::size_t i = 0; i < result_dirs.size(); ++i) {
    const DriveRecord d = read_drive(result_dirs[i]);
    db::Transaction tx(*db);
    const auto found = db->query("SELECT results_hash FROM drives WHERE drive_key = ?", {d.drive_key});
    if (!found.empty() && db::text(found[0][0]) == d.results_hash) {
      ++sum.drives_unchanged;
    } else {
      if (!found.empty()) db->execute("DELETE FROM drives WHERE drive_key = ?", {d.drive_key});
      ++(found.empty() ? sum.drives_added : sum.drives_replaced);
      insert_owners(*db, d);
      sum.sections_added += insert_sections(*db, d);
      insert_drive(*db, d);
      insert_results(*db, d);
      sum.section_results += static_cast<int>(d.results.size());
    }
    tx.commit();
    if (progress) progress(i + 1);
  }
  return sum;
}

}  // namespace roadload::fleet
