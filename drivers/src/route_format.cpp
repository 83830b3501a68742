#include <cmath>
#include <cstdio>

#include "roadload/content_hash.hpp"
#include "roadload/results/json.hpp"
#include "roadload/route_file.hpp"
#include "roadload/toml_text.hpp"

namespace roadload {
namespace {

// A TOML basic string escapes as a JSON string does: quotes, backslashes, control characters as \uXXXX.

// Fixed decimals: 8 in degrees is a millimetre, 3 in metres is too.
std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

std::string format_route_file(const RouteFile& r) {
  std::string out = "# Route file (docs/simulator.md, \"Route files\"). Elevations are heights above the WGS84 ellipsoid.\n";
  out += "name = " + toml_quoted(r.name) + "\n";
  if (!r.source.empty()) out += "source = " + toml_quoted(r.source) + "\n";
  out += "default_crr = " + fixed(r.default_crr, 5) + "\n";
  out += "default_iri_m_per_km = " + fixed(r.default_iri_m_per_km, 2) + "\n";
  if (!r.grade_file.empty()) out += "grade = " + toml_quoted(r.grade_file) + "\n";
  for (const RoutePoint& p : r.points) {
    out += "\n[[point]]\nlat_deg = " + fixed(p.lat_deg, 8) + "\nlon_deg = " + fixed(p.lon_deg, 8) + "\n";
    if (std::isfinite(p.elev_m)) out += "elev_m = " + fixed(p.elev_m, 3) + "\n";
  }
  for (const CellDef& c : r.cells) {
    // Both ends rounded to the centimetre before the length: cells that touch still touch when read back.
    const double start = std::round(c.start_m * 100) / 100, end = std::round(c.end_m * 100) / 100;
    out += "\n[[cell]]\nid = " + toml_quoted(c.id) + "\nstart_m = " + fixed(start, 2) + "\nlength_m = " + fixed(end - start, 2) +
           "\n";
    if (!c.surface.empty()) out += "surface = " + toml_quoted(c.surface) + "\n";
    if (c.crr) out += "crr = " + fixed(*c.crr, 5) + "\n";
    if (c.iri_m_per_km) out += "iri_m_per_km = " + fixed(*c.iri_m_per_km, 2) + "\n";
    if (c.iso8608_class) out += "iso8608_class = \"" + std::string(1, *c.iso8608_class) + "\"\n";
    if (c.joint_spacing_m > 0) out += "joint_spacing_m = " + fixed(c.joint_spacing_m, 2) + "\n";
  }
  return out;
}

std::string route_hash(const RouteFile& r) {
  std::string canonical;
  for (const RoutePoint& p : r.points) canonical += fixed(p.lat_deg, 8) + "," + fixed(p.lon_deg, 8) + ";";
  for (const CellDef& c : r.cells) canonical += "\n" + c.id + "," + fixed(c.start_m, 2) + "," + fixed(c.end_m, 2) + "," + c.surface;
  return content_hash(canonical);
}

}  // namespace roadload
