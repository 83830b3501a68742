// roadload route build: a route file made from the user's own drives, for a road nobody surveyed
// or whose survey is not at hand: the longest GNSS pass traces the polyline, every pass's heights
// give its grade with a standard error (as `roadload grade`), and the cells are of a fixed length
// or the pavement sections of a GIS file.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "gnss_tracks.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/geo_files.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/route_file.hpp"
#include "roadload/track_route.hpp"

namespace roadload::cli {
namespace {

const HelpText kRouteHelp{"usage: roadload route build RECORDING... --out FILE [--cell-length M | --sections FILE] [options]",
                          "Makes a route file from the recordings' own GNSS (gnss.csv, else the truck's J1939 VP1 with VDS's\n"
                          "altitude). The longest pass traces the road; each recording is cut into passes where it turns\n"
                          "back on itself. The route runs the way the first recording's first pass drives: analyze follows\n"
                          "a drive along its route, so a road driven both ways gets two routes from the same recordings,\n"
                          "each with a recording of its direction first. Every pass's heights, less the antenna's height, give the\n"
                          "grade per bin with its standard error, written beside FILE as FILE's stem + .grade.csv and named\n"
                          "by the route file: from several passes the scatter of their slopes, from one pass a GNSS height's\n"
                          "error over the slope's base (0.5 % of grade), so the intervals from a lone pass are wide.\n"
                          "Cells carry no CRR: that is what analyze measures. Drive the road both ways, several times."};

struct RouteOptions {
  std::vector<std::string> recordings;
  std::string out, sections, name;
  double cell_length_m = TrackRouteConfig{}.cell_length_m;
  TrackOptions track;
  GradeConfig grade;
  bool quiet = false;
};

// A route's own GNSS heights carry a few decimetres of white noise per fix: over +-30 m that is
// 0.2 % of grade per bin, over +-60 m half of it. A longer base flattens the road's own swells
// (3 % of a 1.1 km wave's grade at +-100 m), and the mass the filter finds on them follows. The
// filter carries the errors as correlated over the window (120 m).
constexpr double kTracedSlopeBase_m = 60.0;

void add_options(CLI::App& cmd, RouteOptions& o) {
  o.grade.min_passes = 1;
  o.grade.base_m = kTracedSlopeBase_m;
  o.grade.pass_slope_sigma = kGnssPassSlopeSigma;
  cmd.add_option("RECORDING", o.recordings, "recording folders whose GNSS traces the road")->required();
  cmd.add_option("-o,--out", o.out, "the route file to write (TOML, docs/simulator.md \"Route files\")")
      ->type_name("FILE")
      ->required();
  CLI::Option* cells = cmd.add_option("--cell-length", o.cell_length_m, "cells of M metres from the route's start (default 250)")
                           ->type_name("M")
                           ->check(real_in(10, 100000));
  cmd.add_option("--sections", o.sections,
                 "cells from the pavement sections of a GeoJSON or GPX file instead:\n"
                 "each section's ends placed on the route; name, surface, panel_length_m\n"
                 "and iri_m_per_km kept when the file gives them")
      ->type_name("FILE")
      ->excludes(cells);
  cmd.add_option("--name", o.name, "the route's name (default: FILE's stem)")->type_name("TEXT");
  cmd.add_option("--vehicle", o.track.vehicle, "vehicle file or built-in name whose antenna height the recordings\nshare")
      ->type_name("V");
  cmd.add_option("--antenna-height", o.track.antenna_height_m, "GNSS antenna above the road, over any vehicle's")
      ->type_name("M")
      ->check(real_in(-10, 20));
  cmd.add_option("--bin", o.grade.bin_m, "grade bin length (default 10)")->type_name("M")->check(real_in(0.5, 1000));
  cmd.add_option("--base", o.grade.base_m, "slope over +-M (default 60); the grade's errors correlate over 2 M")
      ->type_name("M")
      ->check(real_in(0.5, 5000));
  cmd.add_option("--max-offset", o.grade.max_offset_m,
                 "fixes or section ends farther than M from the traced road are\nelsewhere (default 15)")
      ->type_name("M")
      ->check(real_in(0.1, 1000));
  cmd.add_flag("-q,--quiet", o.quiet, "no summary on standard error");
}

// Each point's height: the passes' mean road height in its bin (NaN where no pass had a 3-D fix).
void set_heights(std::vector<GeoPoint>& points, const RouteGeometry& geometry, const GradeProfile& grade) {
  for (GeoPoint& p : points)
    p.elev_m = grade.elevation_m(std::clamp(geometry.project(p.lat_deg, p.lon_deg).s_m, 0.0, geometry.length_m()));
}

std::variant<std::vector<CellDef>, int> section_cells(const RouteOptions& o, const RouteGeometry& geometry) {
  auto loaded = load_geo_sections(o.sections);
  if (!loaded) {
    std::fprintf(stderr, "roadload route: %s\n", loaded.error().to_string().c_str());
    return loaded.error().line > 0 || loaded.error().message != "cannot open" ? kExitDataErr : kExitNoInput;
  }
  const std::vector<GeoSection>& sections = loaded.value();
  std::vector<std::vector<GeoPoint>> lines;
  for (const GeoSection& s : sections) lines.push_back(s.line);
  std::vector<CellDef> cells;
  for (const SectionSpan& span : place_sections(geometry, lines, o.grade.max_offset_m)) {
    const GeoSection& s = sections[span.index];
    const std::string name = s.name.empty() ? s.where : s.name;
    if (!span.skipped.empty()) {
      std::fprintf(stderr, "roadload route: %s: %s: not on the route: %s\n", o.sections.c_str(), name.c_str(), span.skipped.c_str());
      continue;
    }
    CellDef c;
    c.id = name;
    c.start_m = span.start_m;
    c.end_m = span.end_m;
    c.surface = s.surface.value_or("");
    c.iri_m_per_km = s.iri_m_per_km;
    c.joint_spacing_m = s.panel_length_m.value_or(0.0);
    cells.push_back(std::move(c));
  }
  if (cells.empty()) {
    std::fprintf(stderr, "roadload route: %s: no section lies on the route the recordings trace\n", o.sections.c_str());
    return kExitDataErr;
  }
  return cells;
}

std::vector<CellDef> fixed_cells(double length_m, double cell_length_m) {
  std::vector<CellDef> cells;
  for (const CellSpan& span : fixed_length_cells(length_m, cell_length_m)) {
    CellDef c;
    c.id = span.id;
    c.start_m = span.start_m;
    c.end_m = span.end_m;
    cells.push_back(std::move(c));
  }
  return cells;
}

// The cells' mean length: the grade's error is measured over what the cells average it over.
double mean_cell_length_m(const std::vector<CellDef>& cells, double fallback_m) {
  double sum_m = 0;
  for (const CellDef& c : cells) sum_m += c.end_m - c.start_m;
  return cells.empty() || !(sum_m > 0) ? fallback_m : sum_m / static_cast<double>(cells.size());
}

int build(RouteOptions& o) {
  if (o.grade.base_m < o.grade.bin_m) return usage_error("route build", "--base must be at least --bin: a slope needs three bins");
  if (o.name.empty()) o.name = std::filesystem::path(o.out).stem().string();
  j1939::Database db;
  if (auto rc = load_definitions("route", {}, db)) return *rc;
  std::vector<RecordedTrack> tracks(o.recordings.size());
  std::uint64_t malformed = 0;
  std::vector<GnssTrack> gnss;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (auto rc = read_recorded_track("route", {o.recordings[i]}, o.track, db, tracks[i], malformed)) return *rc;
    if (!o.quiet) {
      std::fprintf(stderr, "route: %s: %zu fixes from %s\n", tracks[i].path.c_str(), tracks[i].fixes.size(),
                   tracks[i].fixes.empty() ? "nowhere (no gnss.csv, no VP1)" : tracks[i].source.c_str());
    }
    gnss.push_back({tracks[i].fixes, tracks[i].antenna_height_m});
  }
  TrackRouteConfig trace;
  trace.cell_length_m = std::min(o.cell_length_m, trace.cell_length_m);
  const std::optional<TrackRoute> pass = longest_pass(gnss, trace);
  if (!pass) {
    std::fprintf(stderr, "roadload route: the recordings trace no pass of %.0f m or more: no road to build\n", trace.cell_length_m);
    return kExitDataErr;
  }
  RouteFile route;
  route.name = o.name;
  route.points = pass->points;
  const std::optional<RouteGeometry> geometry = RouteGeometry::build(route.points);
  if (!geometry) {
    std::fprintf(stderr, "roadload route: the longest pass traces no line\n");
    return kExitDataErr;
  }
  if (o.sections.empty()) {
    route.cells = fixed_cells(geometry->length_m(), o.cell_length_m);
  } else {
    auto cells = section_cells(o, *geometry);
    if (const int* rc = std::get_if<int>(&cells)) return *rc;
    route.cells = std::move(std::get<std::vector<CellDef>>(cells));
  }
  GradeConfig grade_cfg = o.grade;
  grade_cfg.correlation_block_m = mean_cell_length_m(route.cells, grade_cfg.correlation_block_m);
  const GradeProfile grade = GradeProfile::from_gnss(*geometry, gnss, grade_cfg);
  set_heights(route.points, *geometry, grade);
  const std::filesystem::path out(o.out);
  const std::filesystem::path grade_path = out.parent_path() / (out.stem().string() + ".grade.csv");
  route.grade_file = grade_path.filename().string();
  route.source = "roadload route build: " + std::to_string(o.recordings.size()) + " recording(s), " + std::to_string(grade.passes()) +
                 " pass(es)" + (o.sections.empty() ? "" : ", sections from " + std::filesystem::path(o.sections).filename().string());
  if (auto e = write_grade_file(grade_path.string(), grade)) {
    std::fprintf(stderr, "roadload route: %s\n", e->to_string().c_str());
    return kExitCantCreate;
  }
  if (auto rc = write_text_file("route", o.out, format_route_file(route))) return *rc;
  if (!o.quiet) {
    const GnssFixCounts& f = grade.fixes();
    double sigma = 0;
    std::size_t n = 0;
    for (const GradeBin& b : grade.bins()) {
      if (!std::isfinite(b.grade_sigma_rad)) continue;
      sigma += b.grade_sigma_rad;
      ++n;
    }
    std::fprintf(
        stderr,
        "route: %s: %.0f m traced by %zu points, %zu cells; %zu passes, fixes %zu used, %zu off the road, %zu without a 3-D fix\n",
        o.out.c_str(), geometry->length_m(), route.points.size(), route.cells.size(), grade.passes(), f.used, f.off_route,
        f.no_3d_fix);
    if (n > 0) {
      std::fprintf(stderr, "route: %s: %zu of %zu bins with a grade, mean grade sigma %.3f %%\n", grade_path.string().c_str(), n,
                   grade.bins().size(), 100 * sigma / static_cast<double>(n));
    } else {
      std::fprintf(stderr, "route: %s: no bin has a grade (no 3-D fix): analyze will not identify a CRR on it\n",
                   grade_path.string().c_str());
    }
  }
  return malformed > 0 ? kExitDataErr : kExitOk;
}

}  // namespace

Run add_route(CLI::App& roadload) {
  auto o = std::make_shared<RouteOptions>();
  CLI::App& build_cmd = add_action_command(
      roadload, "route", "build a route file from the recordings' own GNSS passes, with cells or a GIS file's sections", "build",
      "make a route file from the recordings' GNSS passes", kRouteHelp);
  add_options(build_cmd, *o);
  return [o] { return build(*o); };
}

}  // namespace roadload::cli
