#pragma once
// A route file: a surveyed geodetic polyline with elevation, and the pavement cells along it
// (docs/simulator.md, "Route files"). The simulator drives it; the estimator takes its geometry,
// grade and cell boundaries from it. Plain data: each side draws what it needs.
#include <optional>
#include <string>
#include <vector>

#include "roadload/cell_span.hpp"
#include "roadload/geo_point.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/pavement_groups.hpp"

namespace roadload {

using RoutePoint = GeoPoint;

struct CellDef {
  std::string id;
  double start_m = 0;  // along the polyline from its first point
  double end_m = 0;
  std::string surface;        // "concrete" or "bituminous"; empty where not known
  std::optional<double> crr;  // the pavement's CRR where the file states it (the simulator's truth)
  std::optional<double> iri_m_per_km;
  std::optional<char> iso8608_class;
  double joint_spacing_m = 0;
};

struct RouteFile {
  std::string name;
  std::string source;              // where the geometry and cells come from
  std::string source_file;         // the file it was read from, for errors
  std::vector<RoutePoint> points;  // [[point]] tables, or the GeoJSON or GPX file `geometry` names
  std::string grade_file;          // `grade`: a grade profile with its sigma (`roadload grade`), resolved
  std::vector<CellDef> cells;      // ordered, not overlapping
  double default_crr = 0.0055;
  double default_iri_m_per_km = 1.5;
};

Parsed<RouteFile> load_route_file(const std::string& path);
// The cells' pavement groups (surface and panel length), for spectra per pavement.
PavementGroups pavement_groups(const std::vector<CellDef>& cells);
// The cells as the estimator takes them, with the IRI each states (a class alone is not converted).
std::vector<CellSpan> cell_spans(const std::vector<CellDef>& cells);
// The route as a route file: [[point]] tables (never a geometry file) and `grade` as given.
std::string format_route_file(const RouteFile& route);
// What makes two route files the same road cut the same way (the points and each cell's id, ends
// and surface; not the name, notes or CRR guesses): the key a fleet's results are merged on.
std::string route_hash(const RouteFile& route);
// A route argument: a route file, or the name of a built-in route (data_dir()/routes/NAME.toml).
std::string resolve_route(const std::string& name_or_path);

}  // namespace roadload
