#pragma once
// A road as the plant drives it: a geodetic polyline with elevation, and cells (pavement test
// sections) with surface, CRR and roughness. Distances are metres along the polyline from its
// first point; positions before and after it extend along the end bearings so a truck can run in.
#include <GeographicLib/GeodesicLine.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/route_file.hpp"
#include "roadload/sim/road_profile.hpp"

namespace roadload::sim {

struct Cell {
  std::string id;
  double start_m = 0;
  double end_m = 0;
  std::string surface;         // "concrete" or "bituminous"
  double crr = 0;              // the tire-pavement CRR at 14.3 C, 30 mph, warm tires: the truth
  double gd_n0_m3 = 0;         // ISO 8608 roughness
  double joint_spacing_m = 0;  // concrete panels; 0 for none
};

struct RouteDef {
  std::string name;
  std::string source;       // where the geometry and cells come from
  std::string source_file;  // the file it was read from, for errors
  std::vector<RoutePoint> points;
  std::vector<Cell> cells;  // in order, not overlapping
  double default_crr = 0.0055;
  double default_gd_n0_m3 = 8e-6;
};

// Reads a route file (roadload/route_file.hpp) and turns roughness into ISO 8608 G_d(n0).
Parsed<RouteDef> load_route(const std::string& path);

class Route {
 public:
  // Needs at least two points; cells must be ordered and inside the route.
  static Parsed<Route> build(RouteDef def);

  struct Position {
    double lat_deg, lon_deg, heading_deg, elev_m;
  };

  const RouteDef& def() const { return *def_; }
  double length_m() const { return cumulative_m_.back(); }
  Position at(double s_m) const;
  // The heading alone, as at() gives it: the plant needs it every step, the position it does not.
  double heading_deg(double s_m) const;
  double elevation_m(double s_m) const;  // surveyed elevation, smoothed over 60 m as a road is built
  double grade_rad(double s_m) const;
  // The cell at s, or nullptr between cells.
  const Cell* cell_at(double s_m) const;
  double crr_at(double s_m) const;
  // Roughness and joints covering [from_m, to_m] with no gaps (gaps take the route defaults).
  std::vector<ProfileSegment> profile_segments(double from_m, double to_m, double faulting_m, double curl_m) const;

 private:
  Route() = default;
  std::size_t segment_at(double s_m) const;
  std::shared_ptr<const RouteDef> def_;
  std::vector<double> cumulative_m_;  // distance at each point
  // The geodesic leaving each point, set up once: setting one up costs as much as walking it.
  std::vector<GeographicLib::GeodesicLine> lines_;
  // Smoothed elevation every kElevationStep_m from elev_origin_m.
  std::vector<double> elevation_;
  double elev_origin_m_ = 0;
};

}  // namespace roadload::sim
