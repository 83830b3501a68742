#include "roadload/route_file.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "roadload/definitions.hpp"
#include "roadload/geo_files.hpp"
#include "roadload/toml_fields.hpp"

namespace roadload {
namespace {

CellDef read_cell(const detail::TomlFields& f, const toml::table& t, std::size_t index) {
  const std::string where = "cell[" + std::to_string(index) + "].";
  f.only(t, {"id", "start_m", "length_m", "surface", "crr", "iri_m_per_km", "iso8608_class", "joint_spacing_m"}, where);
  CellDef c;
  c.id = f.required_text(t, "id", where);
  c.start_m = f.required_number(t, "start_m", where);
  c.end_m = c.start_m + f.required_number(t, "length_m", where);
  if (!(c.end_m > c.start_m)) f.fail(t.get("length_m"), where + "length_m", "must be positive");
  c.surface = f.text(t, "surface", where).value_or("");
  if (!c.surface.empty() && c.surface != "concrete" && c.surface != "bituminous") {
    f.fail(t.get("surface"), where + "surface", "expected \"concrete\" or \"bituminous\"");
  }
  // Only the simulator needs a true CRR; a route made to measure a road has none.
  c.crr = f.number(t, "crr", where);
  if (c.crr && !(*c.crr > 0 && *c.crr <= 0.05)) f.fail(t.get("crr"), where + "crr", "outside 0..0.05");
  c.iri_m_per_km = f.number(t, "iri_m_per_km", where);
  if (c.iri_m_per_km && !(*c.iri_m_per_km > 0 && *c.iri_m_per_km < 50))
    f.fail(t.get("iri_m_per_km"), where + "iri_m_per_km", "outside 0..50 m/km");
  if (auto cls = f.text(t, "iso8608_class", where)) {
    if (cls->size() != 1 || (*cls)[0] < 'A' || (*cls)[0] > 'H') {
      f.fail(t.get("iso8608_class"), where + "iso8608_class", "expected A..H");
    }
    c.iso8608_class = (*cls)[0];
  }
  c.joint_spacing_m = f.number(t, "joint_spacing_m", where, 0.0);
  if (c.joint_spacing_m < 0) f.fail(t.get("joint_spacing_m"), where + "joint_spacing_m", "negative");
  return c;
}

std::vector<RoutePoint> read_points(const detail::TomlFields& f, const toml::table& root) {
  const toml::array* points = root["point"].as_array();
  if (points == nullptr || points->size() < 2) f.fail(&root, "point", "at least two [[point]] tables, or a geometry file, required");
  std::vector<RoutePoint> out;
  for (std::size_t i = 0; i < points->size(); ++i) {
    const toml::table* t = (*points)[i].as_table();
    const std::string where = "point[" + std::to_string(i) + "].";
    if (t == nullptr) f.fail(&(*points)[i], where, "expected a table");
    f.only(*t, {"lat_deg", "lon_deg", "elev_m"}, where);
    RoutePoint p;
    p.lat_deg = f.required_number(*t, "lat_deg", where);
    p.lon_deg = f.required_number(*t, "lon_deg", where);
    // A route without a survey still has geometry and cells; the estimator says where grade is missing.
    p.elev_m = f.number(*t, "elev_m", where).value_or(std::numeric_limits<double>::quiet_NaN());
    if (std::abs(p.lat_deg) > 90) f.fail(t->get("lat_deg"), where + "lat_deg", "outside -90..90");
    if (std::abs(p.lon_deg) > 180) f.fail(t->get("lon_deg"), where + "lon_deg", "outside -180..180");
    out.push_back(p);
  }
  return out;
}

// A file a route names, relative to the route file's own folder.
std::string beside(const std::string& route_path, const std::string& name) {
  const std::filesystem::path p(name);
  if (p.is_absolute()) return name;
  return (std::filesystem::path(route_path).parent_path() / p).string();
}

}  // namespace

Parsed<RouteFile> load_route_file(const std::string& path) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const toml::table& root = parsed.value();
  detail::TomlFields f(path);
  try {
    f.only(root, {"name", "source", "default_crr", "default_iri_m_per_km", "geometry", "grade", "point", "cell"}, "");
    RouteFile d;
    d.source_file = path;
    d.name = f.required_text(root, "name", "");
    d.source = f.text(root, "source", "").value_or("");
    d.default_crr = f.number(root, "default_crr", "", d.default_crr);
    if (!(d.default_crr > 0 && d.default_crr <= 0.05)) f.fail(root.get("default_crr"), "default_crr", "outside 0..0.05");
    d.default_iri_m_per_km = f.number(root, "default_iri_m_per_km", "", d.default_iri_m_per_km);
    if (!(d.default_iri_m_per_km > 0 && d.default_iri_m_per_km < 50)) {
      f.fail(root.get("default_iri_m_per_km"), "default_iri_m_per_km", "outside 0..50 m/km");
    }
    if (auto geometry = f.text(root, "geometry", "")) {
      if (root.contains("point")) f.fail(root.get("geometry"), "geometry", "give the geometry or [[point]] tables, not both");
      auto line = load_geo_line(beside(path, *geometry));
      if (!line) return line.error();
      d.points = std::move(line.value());
    } else {
      d.points = read_points(f, root);
    }
    if (auto grade = f.text(root, "grade", "")) d.grade_file = beside(path, *grade);
    if (const toml::array* cells = root["cell"].as_array()) {
      for (std::size_t i = 0; i < cells->size(); ++i) {
        const toml::table* t = (*cells)[i].as_table();
        if (t == nullptr) f.fail(&(*cells)[i], "cell[" + std::to_string(i) + "]", "expected a table");
        CellDef c = read_cell(f, *t, i);
        if (!d.cells.empty() && c.start_m < d.cells.back().end_m - 1e-6) {
          f.fail(t, "cell[" + std::to_string(i) + "].start_m", "overlaps the previous cell");
        }
        d.cells.push_back(std::move(c));
      }
    }
    return d;
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
}

std::vector<CellSpan> cell_spans(const std::vector<CellDef>& cells) {
  std::vector<CellSpan> out;
  for (const CellDef& c : cells)
    out.push_back({c.id, c.start_m, c.end_m, c.iri_m_per_km.value_or(std::numeric_limits<double>::quiet_NaN())});
  return out;
}

PavementGroups pavement_groups(const std::vector<CellDef>& cells) {
  std::vector<PavementKey> keys;
  for (const CellDef& c : cells) keys.push_back({c.surface, c.joint_spacing_m});
  return group_pavements(keys);
}

std::string resolve_route(const std::string& name_or_path) {
  if (std::filesystem::exists(name_or_path)) return name_or_path;
  return data_dir() + "/routes/" + name_or_path + ".toml";
}

}  // namespace roadload
