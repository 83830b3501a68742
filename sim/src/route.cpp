#include "roadload/sim/route.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>
#include <algorithm>
#include <cmath>

namespace roadload::sim {
namespace {

constexpr double kElevationStep_m = 1.0;
constexpr double kElevationSmooth_m = 60.0;
constexpr double kRunIn_m = 2000.0;  // elevation and geometry defined this far beyond both ends

double raw_elevation(const RouteDef& d, const std::vector<double>& cum, double s) {
  if (s <= 0) return d.points.front().elev_m;
  if (s >= cum.back()) return d.points.back().elev_m;
  const auto i = static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin()) - 1;
  const double w = (s - cum[i]) / (cum[i + 1] - cum[i]);
  return d.points[i].elev_m + w * (d.points[i + 1].elev_m - d.points[i].elev_m);
}

}  // namespace

Parsed<RouteDef> load_route(const std::string& path) {
  auto file = load_route_file(path);
  if (!file) return file.error();
  const RouteFile& rf = file.value();
  RouteDef d;
  d.name = rf.name;
  d.source = rf.source;
  d.source_file = rf.source_file;
  d.points = rf.points;
  d.default_crr = rf.default_crr;
  d.default_gd_n0_m3 = gd_from_iri_m3(rf.default_iri_m_per_km);
  for (const CellDef& c : rf.cells) {
    // A cell's roughness: its IRI, else its ISO 8608 class, else the route's default.
    double gd = d.default_gd_n0_m3;
    if (c.iri_m_per_km) {
      gd = gd_from_iri_m3(*c.iri_m_per_km);
    } else if (c.iso8608_class) {
      gd = iso8608_class_gd_m3(*c.iso8608_class);
    }
    d.cells.push_back({c.id, c.start_m, c.end_m, c.surface, c.crr.value_or(rf.default_crr), gd, c.joint_spacing_m});
  }
  return d;
}

Parsed<Route> Route::build(RouteDef def) {
  if (def.points.size() < 2) return ParseError{def.name, 0, "point", "a route needs at least two points"};
  // Errors name the route by its file when it has one.
  const std::string where = def.source_file.empty() ? def.name : def.source_file;
  const auto& geod = GeographicLib::Geodesic::WGS84();
  Route r;
  r.cumulative_m_.push_back(0.0);
  for (std::size_t i = 0; i < def.points.size(); ++i) {
    if (std::isnan(def.points[i].elev_m)) {
      return ParseError{where, 0, "point[" + std::to_string(i) + "].elev_m", "the simulator needs every point's elevation"};
    }
  }
  for (std::size_t i = 0; i + 1 < def.points.size(); ++i) {
    double s12 = 0, azi1 = 0, azi2 = 0;
    geod.Inverse(def.points[i].lat_deg, def.points[i].lon_deg, def.points[i + 1].lat_deg, def.points[i + 1].lon_deg, s12, azi1, azi2);
    if (s12 < 1e-3) return ParseError{where, 0, "point[" + std::to_string(i + 1) + "]", "repeats the previous point"};
    r.cumulative_m_.push_back(r.cumulative_m_.back() + s12);
    // Route::at's caps are those Geodesic::Direct gives its own line, so positions keep its bits.
    r.lines_.emplace_back(geod, def.points[i].lat_deg, def.points[i].lon_deg, azi1,
                          GeographicLib::GeodesicLine::LATITUDE | GeographicLib::GeodesicLine::LONGITUDE |
                              GeographicLib::GeodesicLine::AZIMUTH | GeographicLib::GeodesicLine::DISTANCE_IN);
  }
  for (const Cell& c : def.cells) {
    if (c.start_m < 0 || c.end_m > r.cumulative_m_.back() + 1e-6 || c.end_m <= c.start_m) {
      return ParseError{where, 0, "cell " + c.id,
                        "lies outside the route (" + std::to_string(r.cumulative_m_.back()) + " m) or has no length"};
    }
  }
  // Smooth the polyline's elevation as a road is graded: grade must not jump at survey points.
  r.elev_origin_m_ = -kRunIn_m;
  const auto n = static_cast<std::size_t>((r.cumulative_m_.back() + 2 * kRunIn_m) / kElevationStep_m) + 1;
  std::vector<double> raw(n);
  for (std::size_t i = 0; i < n; ++i) {
    raw[i] = raw_elevation(def, r.cumulative_m_, r.elev_origin_m_ + static_cast<double>(i) * kElevationStep_m);
  }
  const auto half = static_cast<std::size_t>(kElevationSmooth_m / kElevationStep_m / 2);
  r.elevation_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i > half ? i - half : 0;
    const std::size_t hi = std::min(n - 1, i + half);
    double sum = 0;
    for (std::size_t j = lo; j <= hi; ++j) sum += raw[j];
    r.elevation_[i] = sum / static_cast<double>(hi - lo + 1);
  }
  r.def_ = std::make_shared<const RouteDef>(std::move(def));
  return r;
}

std::size_t Route::segment_at(double s_m) const {
  if (s_m >= cumulative_m_.back()) return lines_.size() - 1;
  if (s_m <= 0) return 0;
  return static_cast<std::size_t>(std::upper_bound(cumulative_m_.begin(), cumulative_m_.end(), s_m) - cumulative_m_.begin()) - 1;
}

Route::Position Route::at(double s_m) const {
  const std::size_t i = segment_at(s_m);
  double lat = 0, lon = 0, azi2 = 0;
  lines_[i].Position(s_m - cumulative_m_[i], lat, lon, azi2);
  const double heading = std::fmod(azi2 + 360.0, 360.0);
  return {lat, lon, heading, elevation_m(s_m)};
}

double Route::heading_deg(double s_m) const {
  const std::size_t i = segment_at(s_m);
  double lat = 0, lon = 0, azi2 = 0;
  lines_[i].GenPosition(false, s_m - cumulative_m_[i], GeographicLib::GeodesicLine::AZIMUTH, lat, lon, azi2, lat, lat, lat, lat, lat);
  return std::fmod(azi2 + 360.0, 360.0);
}

double Route::elevation_m(double s_m) const {
  const double u = std::clamp((s_m - elev_origin_m_) / kElevationStep_m, 0.0, static_cast<double>(elevation_.size() - 2));
  const auto i = static_cast<std::size_t>(u);
  const double w = u - static_cast<double>(i);
  return elevation_[i] + w * (elevation_[i + 1] - elevation_[i]);
}

double Route::grade_rad(double s_m) const {
  constexpr double h = 5.0;
  return std::atan((elevation_m(s_m + h) - elevation_m(s_m - h)) / (2 * h));
}

const Cell* Route::cell_at(double s_m) const {
  const auto& cells = def_->cells;
  auto it = std::upper_bound(cells.begin(), cells.end(), s_m, [](double s, const Cell& c) { return s < c.start_m; });
  if (it == cells.begin()) return nullptr;
  --it;
  return s_m < it->end_m ? &*it : nullptr;
}

double Route::crr_at(double s_m) const {
  const Cell* c = cell_at(s_m);
  return c != nullptr ? c->crr : def_->default_crr;
}

std::vector<ProfileSegment> Route::profile_segments(double from_m, double to_m, double faulting_m, double curl_m) const {
  std::vector<ProfileSegment> out;
  double at = from_m;
  auto filler = [&](double end) {
    if (end > at) out.push_back({at, end, def_->default_gd_n0_m3, {}});
  };
  for (const Cell& c : def_->cells) {
    if (c.end_m <= from_m || c.start_m >= to_m) continue;
    filler(c.start_m);
    ProfileSegment seg{std::max(c.start_m, from_m), std::min(c.end_m, to_m), c.gd_n0_m3, {}};
    if (c.joint_spacing_m > 0) {
      seg.joints.spacing_m = c.joint_spacing_m;
      seg.joints.faulting_m = faulting_m;
      seg.joints.curl_m = curl_m;
    }
    out.push_back(seg);
    at = seg.end_m;
  }
  filler(to_m);
  return out;
}

}  // namespace roadload::sim
