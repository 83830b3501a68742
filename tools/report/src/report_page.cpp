#include "roadload/report/report_page.hpp"

#include <cmath>
#include <map>

#include "roadload/fuel_breakdown.hpp"
#include "roadload/report/html_blocks.hpp"
#include "roadload/report/report_answer.hpp"
#include "roadload/report/report_figures.hpp"
#include "roadload/report/report_gap.hpp"

namespace roadload::report {
namespace {

using results::JsonValue;
using results::NumberTable;

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:1em auto;padding:0 1em;color:#222}"
    "h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:2em}"
    "figure{margin:1em 0}figure svg{width:100%;max-width:760px;height:auto}figcaption{font-size:.9em;color:#444}"
    "table{border-collapse:collapse;font-size:.85em;margin:.5em 0}th,td{border:1px solid #ccc;padding:2px 6px;text-align:right}"
    "h3{font-size:1.05em}th{background:#f3f3f3}td:first-child,th:first-child{text-align:left}.summary td{text-align:left}"
    ".warn{color:#a00}nav a{margin-right:1em}.answer td:last-child{text-align:left;max-width:32em}"
    ".answer{font-size:1em}.provenance{font-size:.9em;color:#333}";

double at(const NumberTable& t, std::size_t row, const std::string& column) {
  const auto c = t.column(column);
  return c ? t.at(row, *c) : std::nan("");
}

// With accelerometers, the tires' own CRR follows the force balance's, and the truth (the simulator's
// tire CRR) is judged against it: like with like.
std::string cell_table(const NumberTable& cells, const results::Truth* truth) {
  const bool tires = cells.column("crr_tire").has_value();
  const std::string judged = tires ? "crr_tire" : "crr";
  std::vector<std::string> head = {"cell",     "from (m)",  "to (m)",      "samples",           "CRR",
                                   "90 % low", "90 % high", "speed (m/s)", "rolling force (N)", "rolling fuel (L)"};
  if (tires) head.insert(head.begin() + 7, {"tires' CRR", "90 % low", "90 % high"});
  const std::size_t truth_at = tires ? 10 : 7;
  if (truth) head.insert(head.begin() + static_cast<std::ptrdiff_t>(truth_at), {"truth", "inside"});
  head.push_back("note");
  std::vector<std::vector<std::string>> rows;
  const std::vector<std::string> ids = cell_ids(cells);
  const std::size_t reason = *cells.column("reason");
  for (std::size_t r = 0; r < cells.rows(); ++r) {
    std::vector<std::string> row = {ids[r],
                                    format_number(at(cells, r, "start_m"), 6),
                                    format_number(at(cells, r, "end_m"), 6),
                                    format_number(at(cells, r, "samples"), 8),
                                    format_number(at(cells, r, "crr"), 4),
                                    format_number(at(cells, r, "crr_lo"), 4),
                                    format_number(at(cells, r, "crr_hi"), 4),
                                    format_number(at(cells, r, "speed_mps"), 3),
                                    format_number(at(cells, r, "roll_force_n"), 4),
                                    format_number(at(cells, r, "rolling_l"), 3)};
    if (tires) {
      row.insert(row.begin() + 7, {format_number(at(cells, r, "crr_tire"), 4), format_number(at(cells, r, "crr_tire_lo"), 4),
                                   format_number(at(cells, r, "crr_tire_hi"), 4)});
    }
    if (truth) {
      const auto it = truth->crr.find(ids[r]);
      const double t = it == truth->crr.end() ? std::nan("") : it->second;
      const bool inside = t >= at(cells, r, judged + "_lo") && t <= at(cells, r, judged + "_hi");
      const bool judgeable = std::isfinite(t) && std::isfinite(at(cells, r, judged));
      row.insert(row.begin() + static_cast<std::ptrdiff_t>(truth_at),
                 {format_number(t, 4), judgeable ? (inside ? "yes" : "no") : ""});
    }
    row.push_back(cells.text(r, reason));
    rows.push_back(std::move(row));
  }
  return table_html(head, rows);
}

std::string trip_fuel_table(const JsonValue& trip) {
  std::vector<std::vector<std::string>> rows;
  double total = 0;
  for (std::size_t i = 0; i < kFuelUseCount; ++i)
    total += trip.number_at(std::string("fuel.") + to_string(static_cast<FuelUse>(i)) + "_l").value_or(0);
  for (std::size_t i = 0; i < kFuelUseCount; ++i) {
    const std::string name = to_string(static_cast<FuelUse>(i));
    const double l = trip.number_at("fuel." + name + "_l").value_or(std::nan(""));
    rows.push_back({name, format_number(l, 4), format_number(total > 0 ? 100 * l / total : std::nan(""), 3)});
  }
  rows.push_back({"measured (fuel rate)", format_number(trip.number_at("fuel.measured_l").value_or(std::nan("")), 4), ""});
  rows.push_back({"not split (closure)", format_number(trip.number_at("fuel.unsplit_l").value_or(std::nan("")), 4), ""});
  return table_html({"use", "diesel (L)", "share (%)"}, rows);
}

std::string dynamic_table(const JsonValue& trip) {
  const JsonValue* groups = pavement_groups(trip);
  if (!groups) return "";
  std::vector<std::vector<std::string>> rows;
  for (const JsonValue& g : groups->items()) {
    const JsonValue* found = g.find("joint_line") ? g.find("joint_line")->find("found") : nullptr;
    const double inventory_m = g.number_at("joint_line.inventory_panel_m").value_or(0);  // 0: no panels (bituminous)
    rows.push_back(
        {g.find("name") ? g.find("name")->string() : "?", format_number(g.number_at("damper_power_w").value_or(NAN), 4),
         format_number(g.number_at("tire_power_w").value_or(NAN), 4), format_number(g.number_at("speed_mps").value_or(NAN), 3),
         found && found->boolean() ? format_number(g.number_at("joint_line.panel_m").value_or(NAN), 3) + " m" : "none found",
         format_number(inventory_m > 0 ? inventory_m : NAN, 3)});
  }
  return table_html({"pavement group", "dampers (W)", "tires (W)", "speed (m/s)", "joint line", "inventory panel (m)"}, rows);
}

// What the drive's data allowed: how much of it the force balance could use and why not the rest,
// how GNSS matched the route and whether the filter's innovations were as large as it expected.
std::string sync_health(const JsonValue& trip) {
  const auto n = [&](const std::string& path) { return trip.number_at(path).value_or(std::nan("")); };
  const double ticks = n("ticks"), usable = n("usable_ticks");
  std::vector<std::vector<std::string>> rows = {
      {"force-balance ticks", format_number(ticks, 8)},
      {"usable", format_number(usable, 8) + " (" + format_number(ticks > 0 ? 100 * usable / ticks : NAN, 3) + " %)"},
  };
  if (const JsonValue* u = trip.find("unusable")) {
    for (const auto& [why, count] : u->members()) {
      if (count.is_number() && count.number() > 0) rows.push_back({"  not usable: " + why, format_number(count.number(), 8)});
    }
  }
  const double nis = n("mean_nis"), band = n("mean_nis_95");
  rows.push_back({"GNSS fixes used", format_number(n("gnss_used"), 8)});
  rows.push_back({"GNSS fixes off the route", format_number(n("gnss_off_route"), 8)});
  rows.push_back({"speed outliers gated", format_number(n("speed_outliers"), 8)});
  rows.push_back(
      {"mean speed NIS (1 when stamps and model agree)", format_number(nis, 3) + " \u00b1 " + format_number(band, 2) +
                                                             (std::abs(nis - 1) > band ? "  \u26a0 outside its 95 % band" : "")});
  rows.push_back({"ticks without a fuel rate", format_number(n("fuel.ticks_without_fuel_rate"), 8)});
  return table_html({"sync and data health", "value"}, rows, "summary");
}

// Each axle's contact force over the cells it was measured on: mean (its static load), standard
// deviation and its dynamic part's, averaged over the cells.
std::string contact_table(const NumberTable& cells) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& a : axle_names(cells)) {
    std::vector<std::string> row{a};
    for (const char* what : {"_mean_n", "_std_n", "_dynamic_std_n"}) {
      double sum = 0;
      std::size_t n = 0;
      for (double v : cells.values("fz_" + a + what)) {
        if (!std::isfinite(v)) continue;
        sum += v;
        ++n;
      }
      row.push_back(format_number(n > 0 ? sum / static_cast<double>(n) / 1000 : NAN, 4));
    }
    rows.push_back(std::move(row));
  }
  return table_html({"axle", "mean (kN)", "standard deviation (kN)", "of it dynamic (kN)"}, rows);
}

// A spectrum with a positive value somewhere: a pavement the drive never reached has none.
bool has_data(const results::Spectrum& s) {
  for (const auto& psd : s.psd) {
    for (double v : psd) {
      if (std::isfinite(v) && v > 0) return true;
    }
  }
  return false;
}

std::string summary(const JsonValue& trip, const NumberTable& cells) {
  const auto n = [&](const std::string& path) { return trip.number_at(path).value_or(std::nan("")); };
  const JsonValue* ident = trip.find("crr_identified");
  const bool identified = ident && ident->boolean();
  std::size_t estimated = 0;
  for (double v : cells.values("crr")) estimated += std::isfinite(v) ? 1 : 0;
  const std::vector<std::vector<std::string>> rows = {
      {"distance", format_number(n("fuel.distance_m") / 1000, 4) + " km"},
      {"fuel measured", format_number(n("fuel.measured_l"), 4) + " L"},
      {"trip CRR", format_number(n("crr"), 4) + " \u00b1 " + format_number(n("crr_sigma"), 2) +
                       (identified ? "" : "  (not identifiable from this drive)")},
      {"CdA", format_number(n("cda_m2"), 4) + " m\u00b2"},
      {"cells with a CRR", std::to_string(estimated) + " of " + std::to_string(cells.rows())},
      {"dynamic rolling resistance", format_number(n("dynamic_rolling.l_per_100km"), 3) + " L/100 km"},
  };
  return table_html({"trip", ""}, rows, "summary");
}

}  // namespace

std::string render_report(const ReportInput& in) {
  const results::ResultsDir& r = *in.results;
  const NumberTable& cells = r.cells;
  std::string body;
  body += "<h1>" + escape_html(in.title) + "</h1>\n<p>Results from <code>" + escape_html(r.dir) + "</code>" +
          (in.truth ? ", beside the simulation's ground truth" : "") + ".</p>\n";
  body +=
      "<nav><a href=\"#answer\">per pavement</a><a href=\"#crr\">CRR</a><a href=\"#fuel\">fuel</a><a href=\"#forces\">contact "
      "forces</a>"
      "<a href=\"#dynamic\">dynamic rolling resistance</a><a href=\"#spectra\">spectra</a><a href=\"#health\">sync health</a>";
  if (r.gap || r.gap_tables) body += "<a href=\"#gap\">sim-to-real gap</a>";
  body += "</nav>\n";
  body += "<h2 id=\"answer\">Per pavement</h2>\n" + answer_section(r.trip);
  body += summary(r.trip, cells);
  body += "<h2 id=\"crr\">Rolling resistance per cell</h2>\n" + figure_html(crr_per_cell(cells, in.truth)) +
          cell_table(cells, in.truth);
  body += "<h2 id=\"fuel\">Fuel</h2>\n" + figure_html(rolling_fuel_per_cell(cells)) + figure_html(fuel_breakdown_per_cell(cells));
  body += figure_html(trip_fuel_breakdown(r.trip, in.truth)) + trip_fuel_table(r.trip);
  body += "<h2 id=\"forces\">Contact forces</h2>\n";
  if (auto f = contact_forces(cells)) {
    body += figure_html(*f) + contact_table(cells);
  } else {
    body += "<p class=\"warn\">No contact forces: the drive had no usable accelerometers.</p>\n";
  }
  body += "<h2 id=\"dynamic\">Dynamic rolling resistance</h2>\n";
  if (auto f = dynamic_power_per_cell(cells, in.truth)) {
    body += figure_html(*f) + dynamic_table(r.trip);
  } else {
    body += "<p class=\"warn\">No dynamic rolling resistance: the drive had no usable accelerometers.</p>\n";
  }
  body += "<h2 id=\"spectra\">Spectra</h2>\n";
  for (const results::Spectrum& s : r.spectra) {
    if (has_data(s)) {
      body += figure_html(spectrum(s, r.trip));
    } else {
      body += "<p class=\"warn\">No spectrum on " + escape_html(s.group) + ": no accelerometer sample was taken on it.</p>\n";
    }
  }
  if (r.spectra.empty()) body += "<p class=\"warn\">No spectra in the results.</p>\n";
  body += "<h2 id=\"health\">Sync health</h2>\n" + sync_health(r.trip);
  body += gap_section(r.gap ? &*r.gap : nullptr, r.gap_tables ? &*r.gap_tables : nullptr);
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + escape_html(in.title) + "</title><style>" +
         kStyle + "</style></head><body>\n" + body + "</body></html>\n";
}

}  // namespace roadload::report
