#pragma once
// Road geometry and pavement sections from GIS files, as agencies keep them: GeoJSON (RFC 7946,
// coordinates longitude, latitude and optional height in WGS84) and GPX 1.1 (tracks and routes,
// <ele> the height). The kind is told by the file's extension: .geojson or .json, .gpx.
#include <optional>
#include <string>
#include <vector>

#include "roadload/geo_point.hpp"
#include "roadload/parse_error.hpp"

namespace roadload {

// A pavement section as a GIS layer draws it: a line along the road and what is known of it.
struct GeoSection {
  std::string name;
  std::vector<GeoPoint> line;            // elev_m NaN where the file gives no height
  std::optional<std::string> surface;    // "concrete" or "bituminous" ("asphalt" is read as bituminous)
  std::optional<double> panel_length_m;  // a jointed concrete pavement's joint spacing
  std::optional<double> iri_m_per_km;
  std::string where;  // the feature in its file, for errors: "features[3]" or "trk[2]"
};

// The one line a file draws (a LineString, or a feature or collection holding just one; a GPX
// file's first track, all its segments, else its first route).
Parsed<std::vector<GeoPoint>> load_geo_line(const std::string& path);
// Every line a file draws, each a section: GeoJSON features with properties name (or id),
// surface, panel_length_m (or joint_spacing_m) and iri_m_per_km; GPX tracks with <name> and
// <type> as the surface.
Parsed<std::vector<GeoSection>> load_geo_sections(const std::string& path);

namespace detail {
Parsed<std::vector<GeoSection>> read_geojson(const std::string& path);
Parsed<std::vector<GeoSection>> read_gpx(const std::string& path);
}  // namespace detail

}  // namespace roadload
