// GeoJSON (RFC 7946) lines and their properties. nlohmann's tree keeps no positions, so an
// error in a value names its path in the document ("features[2].geometry.coordinates[5][1]");
// a syntax error names its line.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>

#include "roadload/geo_files.hpp"

namespace roadload::detail {
namespace {

using nlohmann::json;

struct GeoJsonFailure {
  std::string field, message;
};

[[noreturn]] void fail(std::string field, std::string message) { throw GeoJsonFailure{std::move(field), std::move(message)}; }

double finite(const json& v, const std::string& where) {
  if (!v.is_number()) fail(where, "expected a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(where, "not finite");
  return x;
}

GeoPoint position(const json& p, const std::string& where) {
  if (!p.is_array() || p.size() < 2 || p.size() > 3) fail(where, "expected [longitude, latitude] or [longitude, latitude, height]");
  GeoPoint g{finite(p[1], where + "[1]"), finite(p[0], where + "[0]"), std::numeric_limits<double>::quiet_NaN()};
  if (std::abs(g.lat_deg) > 90) fail(where + "[1]", "latitude outside -90..90");
  if (std::abs(g.lon_deg) > 180) fail(where + "[0]", "longitude outside -180..180");
  if (p.size() == 3) g.elev_m = finite(p[2], where + "[2]");
  return g;
}

void append_line(const json& coords, const std::string& where, std::vector<GeoPoint>& out) {
  if (!coords.is_array()) fail(where, "expected an array of positions");
  for (std::size_t i = 0; i < coords.size(); ++i) out.push_back(position(coords[i], where + "[" + std::to_string(i) + "]"));
}

// A LineString, or a MultiLineString whose parts follow one another along the road.
std::vector<GeoPoint> line_of(const json& geometry, const std::string& where) {
  if (!geometry.is_object()) fail(where, "expected a geometry object");
  const std::string type = geometry.value("type", "");
  std::vector<GeoPoint> line;
  if (type == "LineString") {
    append_line(geometry.value("coordinates", json()), where + ".coordinates", line);
  } else if (type == "MultiLineString") {
    const json& parts = geometry.value("coordinates", json());
    if (!parts.is_array()) fail(where + ".coordinates", "expected an array of lines");
    for (std::size_t i = 0; i < parts.size(); ++i) append_line(parts[i], where + ".coordinates[" + std::to_string(i) + "]", line);
  } else {
    fail(where + ".type", "expected LineString or MultiLineString, found \"" + type + "\"");
  }
  if (line.size() < 2) fail(where + ".coordinates", "a line needs at least two positions");
  return line;
}

std::optional<double> positive(const json& props, std::initializer_list<const char*> keys, const std::string& where, double max) {
  for (const char* k : keys) {
    if (!props.contains(k) || props[k].is_null()) continue;
    const double v = finite(props[k], where + "." + k);
    if (!(v > 0 && v < max)) fail(where + "." + k, "outside 0.." + std::to_string(static_cast<long>(max)));
    return v;
  }
  return std::nullopt;
}

GeoSection section_of(const json& feature, const std::string& where) {
  if (!feature.is_object() || feature.value("type", "") != "Feature") fail(where + ".type", "expected a Feature");
  GeoSection s;
  s.where = where;
  s.line = line_of(feature.value("geometry", json()), where + ".geometry");
  const json props = feature.value("properties", json::object());
  if (!props.is_object() && !props.is_null()) fail(where + ".properties", "expected an object");
  if (props.is_object()) {
    for (const char* k : {"name", "id", "section"}) {
      if (!props.contains(k)) continue;
      s.name = props[k].is_string() ? props[k].get<std::string>() : props[k].dump();
      break;
    }
    if (props.contains("surface") && !props["surface"].is_null()) {
      if (!props["surface"].is_string()) fail(where + ".properties.surface", "expected a string");
      std::string surface = props["surface"].get<std::string>();
      std::transform(surface.begin(), surface.end(), surface.begin(), [](unsigned char c) { return std::tolower(c); });
      if (surface == "asphalt") surface = "bituminous";
      if (surface != "concrete" && surface != "bituminous") {
        fail(where + ".properties.surface", "expected \"concrete\", \"bituminous\" or \"asphalt\"");
      }
      s.surface = surface;
    }
    s.panel_length_m = positive(props, {"panel_length_m", "joint_spacing_m"}, where + ".properties", 100);
    s.iri_m_per_km = positive(props, {"iri_m_per_km"}, where + ".properties", 50);
  }
  return s;
}

long line_at(const std::string& text, std::size_t byte) {
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(std::min(byte, text.size())), '\n'));
}

}  // namespace

Parsed<std::vector<GeoSection>> read_geojson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParseError{path, 0, "", "cannot open"};
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    return ParseError{path, line_at(text, e.byte > 0 ? e.byte - 1 : 0), "", "not JSON: " + std::string(e.what())};
  } catch (const json::exception& e) {
    // A number beyond a double (88e898) is no parse error to the library but an out_of_range.
    return ParseError{path, 1, "", "not JSON that can be read: " + std::string(e.what())};
  }
  try {
    if (!doc.is_object()) fail("", "expected a GeoJSON object");
    const std::string type = doc.value("type", "");
    std::vector<GeoSection> out;
    if (type == "FeatureCollection") {
      const json& features = doc.value("features", json());
      if (!features.is_array()) fail("features", "expected an array");
      for (std::size_t i = 0; i < features.size(); ++i) out.push_back(section_of(features[i], "features[" + std::to_string(i) + "]"));
    } else if (type == "Feature") {
      out.push_back(section_of(doc, "feature"));
    } else {
      GeoSection s;
      s.where = "geometry";
      s.line = line_of(doc, "geometry");
      out.push_back(std::move(s));
    }
    return out;
  } catch (const GeoJsonFailure& f) {
    return ParseError{path, 0, f.field, f.message};
  } catch (const json::exception& e) {
    return ParseError{path, 0, "", e.what()};
  }
}

}  // namespace roadload::detail
