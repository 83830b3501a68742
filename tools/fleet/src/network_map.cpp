#include "network_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "network_text.hpp"
#include "roadload/report/svg_chart.hpp"

namespace roadload::fleet {
namespace {

using report::escape_html;

constexpr double kWidth = 860, kPad = 30, kLaneOffset = 3.5;
constexpr double kAreaKm = 30;  // roads whose centres lie closer share one map

struct Area {
  std::vector<std::size_t> sections;
  double lat0 = 0, lon0 = 0;  // the first road's centre
};

double km_between(double lat_a, double lon_a, double lat_b, double lon_b) {
  const double north = (lat_b - lat_a) * 111.2, east = (lon_b - lon_a) * 111.2 * std::cos(lat_a * std::numbers::pi / 180);
  return std::hypot(north, east);
}

std::vector<Area> areas_of(const NetworkView& v) {
  std::vector<Area> areas;
  for (std::size_t i = 0; i < v.sections.size(); ++i) {
    const NetworkSection& s = v.sections[i];
    if (!s.placed) continue;
    auto near = std::find_if(areas.begin(), areas.end(),
                             [&](const Area& a) { return km_between(a.lat0, a.lon0, s.start_lat, s.start_lon) < kAreaKm; });
    if (near == areas.end()) near = areas.insert(areas.end(), Area{{}, s.start_lat, s.start_lon});
    near->sections.push_back(i);
  }
  return areas;
}

// Viridis at five stops, low CRR dark: a scale readable in grey and by the colour-blind.
std::string colour(double t) {
  static const std::array<std::array<double, 3>, 5> stops{
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const auto i = std::min(static_cast<std::size_t>(t), std::size_t{3});
  const double f = t - static_cast<double>(i);
  char b[16];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", static_cast<int>(stops[i][0] + f * (stops[i + 1][0] - stops[i][0])),
                static_cast<int>(stops[i][1] + f * (stops[i + 1][1] - stops[i][1])),
                static_cast<int>(stops[i][2] + f * (stops[i + 1][2] - stops[i][2])));
  return b;
}

std::string hover(const NetworkSection& s) {
  return s.route + " " + s.cell + " " + s.direction + " (" + s.surface + "): CRR " + csv_number(s.crr.crr, 5) + " [" +
         csv_number(s.crr.crr_lo, 5) + ", " + csv_number(s.crr.crr_hi, 5) + "], " + std::to_string(s.drives) + " drives, " +
         std::to_string(s.trucks) + " trucks";
}

// Long because it lays out one map: the projection, the frame and each section as a lane.
std::string area_svg(const NetworkView& v, const Area& a, double lo, double hi) {
  const double kx = 111.2 * std::cos(a.lat0 * std::numbers::pi / 180), ky = 111.2;
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (std::size_t i : a.sections) {
    const NetworkSection& s = v.sections[i];
    for (const auto& [lat, lon] : {std::pair{s.start_lat, s.start_lon}, std::pair{s.end_lat, s.end_lon}}) {
      x0 = std::min(x0, lon * kx), x1 = std::max(x1, lon * kx), y0 = std::min(y0, lat * ky), y1 = std::max(y1, lat * ky);
    }
  }
  const double span = std::max({x1 - x0, y1 - y0, 0.2});
  const double scale = (kWidth - 2 * kPad) / span;
  const double height = std::max((y1 - y0) * scale + 2 * kPad, 120.0);
  const auto px = [&](double lon) { return kPad + (lon * kx - x0) * scale; };
  const auto py = [&](double lat) { return height - kPad - (lat * ky - y0) * scale; };
  std::string svg = "<svg class=\"map\" viewBox=\"0 0 " + csv_number(kWidth, 0) + " " + csv_number(height, 0) + "\" width=\"" +
                    csv_number(kWidth, 0) + "\" height=\"" + csv_number(height, 0) + "\" role=\"img\">\n";
  for (std::size_t i : a.sections) {
    const NetworkSection& s = v.sections[i];
    double xa = px(s.start_lon), ya = py(s.start_lat), xb = px(s.end_lon), yb = py(s.end_lat);
    // Each direction on its own side of the centre line, as the lanes lie (driving on the right).
    const double len = std::max(std::hypot(xb - xa, yb - ya), 1e-9), nx = -(yb - ya) / len * kLaneOffset,
                 ny = (xb - xa) / len * kLaneOffset;
    xa -= nx, ya -= ny, xb -= nx, yb -= ny;
    const bool known = std::isfinite(s.crr.crr);
    svg += "<path class=\"section\" d=\"M" + csv_number(xa, 1) + " " + csv_number(ya, 1) + " L" + csv_number(xb, 1) + " " +
           csv_number(yb, 1) + "\" stroke=\"" + (known ? colour((s.crr.crr - lo) / (hi - lo)) : std::string("#bbbbbb")) +
           "\" stroke-width=\"6\"" + (known ? "" : " stroke-dasharray=\"4 3\"") + "><title>" + escape_html(hover(s)) +
           "</title></path>\n";
  }
  return svg + "</svg>\n";
}

std::string legend(double lo, double hi) {
  std::string stops;
  for (int i = 0; i <= 4; ++i) stops += "<stop offset=\"" + std::to_string(25 * i) + "%\" stop-color=\"" + colour(i / 4.0) + "\"/>";
  return "<svg class=\"legend\" width=\"420\" height=\"46\"><defs><linearGradient id=\"crr-scale\">" + stops +
         "</linearGradient></defs><rect x=\"10\" y=\"6\" width=\"400\" height=\"14\" fill=\"url(#crr-scale)\"/>"
         "<text x=\"10\" y=\"38\">CRR " +
         csv_number(lo, 5) + "</text><text x=\"410\" y=\"38\" text-anchor=\"end\">" + csv_number(hi, 5) + "</text></svg>\n";
}

std::string table(const NetworkView& v) {
  std::string t =
      "<table><thead><tr><th>Road</th><th>Section</th><th>Dir.</th><th>Surface</th><th>CRR</th><th>90 % interval</th>"
      "<th>Drives</th><th>Trucks</th><th>Dynamic L/100 km</th><th>Rolling L/year</th><th>Dynamic L/year</th></tr></thead><tbody>\n";
  for (const NetworkSection& s : v.sections) {
    t += "<tr><td>" + escape_html(s.route) + "</td><td>" + escape_html(s.cell) + "</td><td>" + s.direction + "</td><td>" +
         escape_html(s.surface) + "</td><td>" + csv_number(s.crr.crr, 5) + "</td><td>" + csv_number(s.crr.crr_lo, 5) + " – " +
         csv_number(s.crr.crr_hi, 5) + "</td><td>" + std::to_string(s.drives) + "</td><td>" + std::to_string(s.trucks) + "</td><td>" +
         csv_number(s.dynamic_l_per_100km, 3) + "</td><td>" + csv_number(s.rolling_l_per_year, 0) + "</td><td>" +
         csv_number(s.dynamic_l_per_year, 0) + "</td></tr>\n";
  }
  return t + "</tbody></table>\n";
}

}  // namespace

std::string network_map(const NetworkView& v) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const NetworkSection& s : v.sections) {
    if (std::isfinite(s.crr.crr)) lo = std::min(lo, s.crr.crr), hi = std::max(hi, s.crr.crr);
  }
  if (!(hi > lo)) lo = std::isfinite(lo) ? lo - 1e-4 : 0.004, hi = lo + 2e-4;
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>roadload network</title><style>"
      "body{font-family:sans-serif;margin:2em;max-width:960px}svg.map{border:1px solid #ccc;margin:0.5em 0}"
      "table{border-collapse:collapse;font-size:0.9em}td,th{border-bottom:1px solid #ddd;padding:2px 8px;text-align:right}"
      "td:nth-child(-n+4),th:nth-child(-n+4){text-align:left}</style></head><body>\n<h1>Rolling resistance by section</h1>\n";
  page += "<p>" + std::to_string(v.drives) + " drives of " + std::to_string(v.trucks.size()) + " trucks over " +
          std::to_string(v.sections.size()) + " sections. " +
          (v.static_crr ? "Static CRR (the tires' on the pavement; the dynamic losses are their own column)"
                        : "CRR of the force balance, dynamic losses included (not every drive measured them)") +
          " at " + csv_number(v.fit.reference_speed_mps * 3.6, 0) +
          " km/h for the fleet's mean truck; the trucks' own offsets spread by " + csv_number(v.fit.truck.sd, 5) + " [" +
          csv_number(v.fit.truck.sd_lo, 5) + ", " + csv_number(v.fit.truck.sd_hi, 5) + "] (90 %). Hover over a section for its " +
          "interval. Each direction is drawn on its own side of the road. Fuel per year at " +
          csv_number(v.options.trucks_per_day, 0) + " trucks a day.</p>\n" + legend(lo, hi);
  for (const Area& a : areas_of(v))
    page += "<h2>" + escape_html(v.sections[a.sections.front()].route) + " and nearby</h2>\n" + area_svg(v, a, lo, hi);
  return page + "<h2>Every section</h2>\n" + table(v) + "</body></html>\n";
}

}  // namespace roadload::fleet
