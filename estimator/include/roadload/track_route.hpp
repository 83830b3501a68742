#pragma once
// A route made from a drive's own GNSS track, for a road nobody surveyed: the fixes thinned to a
// polyline, the road's height the antenna's less its height, and cells of a fixed length along it.
// Its grade comes from the same fixes (GradeProfile::from_gnss); from one pass that grade carries
// the GNSS height's error whole, so the intervals it gives are wide, as they must be.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadload/cell_span.hpp"
#include "roadload/geo_point.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"

namespace roadload {

struct TrackRouteConfig {
  double point_spacing_m = 20.0;  // a fix's noise (a metre or two) moves the polyline's heading by a few degrees at most
  double cell_length_m = 250.0;   // a few hundred metres: the length pavement inventories section roads by
  double max_hdop = 5.0;          // as GradeConfig: beyond it a fix is worse than the road it should trace
  // A pass ends where the track turns back on itself: by more than this within the window.
  double reversal_turn_deg = 150.0;
  double reversal_window_m = 100.0;
};

// A slope's error from one pass of GNSS heights: an error of 0.2 m at each end of the grade
// profile's 60 m base (GradeConfig) is 0.005 of slope, 0.5 % of grade.
inline constexpr double kGnssPassSlopeSigma = 0.005;

struct TrackRoute {
  std::vector<GeoPoint> points;
  std::size_t fixes_used = 0;
};

// The polyline the fixes (in time order) trace; none when they trace less than a cell.
std::optional<TrackRoute> route_from_track(std::span<const GnssFix> fixes, double antenna_height_m,
                                           const TrackRouteConfig& config = {});

// The longest pass of any track (a track cut where it turns back on itself), thinned: the road's
// polyline when nobody surveyed it, running the way the first track's first pass runs. None when
// no pass traces a cell.
std::optional<TrackRoute> longest_pass(std::span<const GnssTrack> tracks, const TrackRouteConfig& config = {});

// A pavement section placed on the route by its ends' projections; `skipped` says why it is not.
struct SectionSpan {
  std::size_t index = 0;  // in the sections given
  double start_m = 0, end_m = 0;
  std::string skipped;
};
// The sections in order along the route, each trimmed to start where the one before it ends.
std::vector<SectionSpan> place_sections(const RouteGeometry& route, std::span<const std::vector<GeoPoint>> lines,
                                        double max_offset_m);

// Cells of `cell_length_m` from the route's start, named by where they start ("250 m"); the last
// one takes the rest, or joins the one before when the rest is under half a cell.
std::vector<CellSpan> fixed_length_cells(double route_length_m, double cell_length_m);

}  // namespace roadload
