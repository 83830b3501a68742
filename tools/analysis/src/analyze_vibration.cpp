#include "analyze_vibration.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "roadload/fuel_breakdown.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/results/json.hpp"

namespace roadload::cli {
namespace {

// Table 6.5's concrete / bituminous damper power on the Mainline (652 / 442 W) and Table 6.6's
// TH 10 / TH 66 (9,353 / 6,486 W).
constexpr double kReportMainlineRatio = 652.0 / 442.0;
constexpr double kReportHighwayRatio = 9353.0 / 6486.0;

// A row of any width: a column per sensor, numbers in scientific notation (densities span decades).
std::optional<ParseError> write_columns(const std::string& path, const char* axis, double bin, const std::vector<std::string>& names,
                                        const std::vector<std::vector<double>>& cols) {
  auto out = recording::OutputFile::create(path);
  if (!out) return out.error();
  std::string line = axis;
  for (const auto& n : names) line += "," + n;
  out.value().write(line + "\n");
  char buf[32];
  for (std::size_t k = 0; !cols.empty() && k < cols.front().size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.6f", static_cast<double>(k) * bin);
    line = buf;
    for (const auto& c : cols) {
      std::snprintf(buf, sizeof buf, ",%.6e", c[k]);
      line += buf;
    }
    out.value().write(line + "\n");
  }
  return out.value().close();
}

}  // namespace

VibrationSummary summarize(const VibrationAnalysis& va, const PavementGroups& groups, double trip_time_s, double trip_distance_m) {
  VibrationSummary s;
  s.trip = va.trip_power();
  const double speed = trip_time_s > 0 ? trip_distance_m / trip_time_s : 0.0;
  s.trip_cost = spectra::stretch_cost(s.trip.total_w(), trip_time_s, speed, kDieselEnergy_jpl);
  s.annual = spectra::annual_cost(s.trip.total_w(), spectra::Duty{}, kDieselEnergy_jpl);
  const auto& modes = va.modes();
  const double spatial_bin = spectra::bin_hz(modes.spatial_welch());
  const double time_bin = spectra::bin_hz(modes.welch());
  for (std::size_t g = 0; g < groups.names.size(); ++g) {
    GroupSpectra out;
    out.name = groups.names[g];
    out.power = va.group_power(g);
    out.speed_mps = modes.mean_speed_mps(static_cast<int>(g));
    out.expected_panel_m = groups.panel_m[g];
    std::vector<std::vector<double>> spatial;
    for (std::size_t i = 0; i < modes.sensor_count(); ++i) spatial.push_back(modes.spatial_density(i, static_cast<int>(g)));
    spectra::JointConfig jc;
    jc.expected_panel_m = groups.panel_m[g];
    out.joint = spectra::find_joint_line(spatial, spatial_bin, jc);
    out.joint_hz = out.joint.found && std::isfinite(out.speed_mps) ? out.speed_mps / out.joint.panel_m : 0.0;
    for (std::size_t i = 0; i < modes.sensor_count(); ++i) {
      auto peaks = spectra::find_peaks(modes.density(i, static_cast<int>(g)), time_bin);
      spectra::label_joint_harmonics(peaks, out.joint_hz, time_bin);
      out.peaks.push_back(std::move(peaks));
    }
    s.groups.push_back(std::move(out));
  }
  return s;
}

std::optional<ParseError> write_psd_files(const std::string& dir, const VibrationAnalysis& va, const PavementGroups& groups) {
  const auto& modes = va.modes();
  std::vector<std::string> names;
  for (std::size_t i = 0; i < modes.sensor_count(); ++i) names.push_back(modes.sensor(i).name);
  for (int g = -1; g < static_cast<int>(groups.names.size()); ++g) {
    std::vector<std::vector<double>> time, spatial;
    for (std::size_t i = 0; i < modes.sensor_count(); ++i) {
      time.push_back(modes.density(i, g));
      spatial.push_back(modes.spatial_density(i, g));
    }
    const std::string suffix = g < 0 ? "" : "-" + groups.names[static_cast<std::size_t>(g)];
    if (auto e = write_columns(dir + "/psd" + suffix + ".csv", "freq_hz", spectra::bin_hz(modes.welch()), names, time)) return e;
    if (g < 0) continue;
    if (auto e = write_columns(dir + "/psd-spatial" + suffix + ".csv", "cycles_per_m", spectra::bin_hz(modes.spatial_welch()), names,
                               spatial))
      return e;
  }
  return std::nullopt;
}

std::string vibration_json(const VibrationSummary& s) {
  std::ostringstream j;
  const auto power = [&](const DynamicPower& p) {
    j << "\"damper_power_w\": " << results::json_number(p.damper_w) << ", \"tire_power_w\": " << results::json_number(p.tire_w)
      << ", \"tire_eq27_power_w\": " << results::json_number(p.tire_eq27_w)
      << ", \"damper_accel_periodogram_w\": " << results::json_number(p.damper_accel_w);
  };
  j << "  \"dynamic_rolling\": {\n    ";
  power(s.trip);
  j << ",\n    \"energy_j\": " << results::json_number(s.trip_cost.energy_j)
    << ", \"liters\": " << results::json_number(s.trip_cost.diesel_l)
    << ", \"l_per_100km\": " << results::json_number(s.trip_cost.l_per_100km)
    << ",\n    \"annual\": {\"hours_per_year\": " << results::json_number(s.annual.hours_per_year)
    << ", \"energy_mj_per_year\": " << results::json_number(s.annual.energy_mj_per_year)
    << ", \"diesel_l_per_year\": " << results::json_number(s.annual.diesel_l_per_year)
    << ", \"l_per_100km\": " << results::json_number(s.annual.l_per_100km) << "},\n    \"groups\": [";
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const GroupSpectra& gs = s.groups[g];
    j << (g ? ",\n" : "\n") << "      {\"name\": " << results::json_quote(gs.name) << ", ";
    power(gs.power);
    j << ", \"speed_mps\": " << (std::isfinite(gs.speed_mps) ? gs.speed_mps : 0.0)
      << ",\n       \"joint_line\": {\"found\": " << (gs.joint.found ? "true" : "false")
      << ", \"panel_m\": " << results::json_number(gs.joint.panel_m) << ", \"freq_hz\": " << results::json_number(gs.joint_hz)
      << ", \"significance\": " << results::json_number(gs.joint.significance)
      << ", \"inventory_panel_m\": " << results::json_number(gs.expected_panel_m) << "},\n       \"modes\": [";
    for (std::size_t i = 0; i < gs.peaks.size(); ++i) {
      j << (i ? ", " : "") << "[";
      for (std::size_t p = 0; p < gs.peaks[i].size(); ++p) {
        const spectra::Peak& pk = gs.peaks[i][p];
        j << (p ? ", " : "") << "{\"freq_hz\": " << results::json_number(pk.freq)
          << ", \"prominence\": " << results::json_number(pk.prominence) << ", \"width_hz\": " << results::json_number(pk.width)
          << ", \"label\": " << results::json_quote(pk.label) << ", \"joint_harmonic\": " << pk.joint_harmonic << "}";
      }
      j << "]";
    }
    j << "]}";
  }
  j << "\n    ]\n  }";
  return j.str();
}

void print_vibration(const VibrationSummary& s) {
  std::fprintf(stderr,
               "analyze: dynamic rolling resistance (Eq. 2.7-2.8): dampers %.0f W, tires %.0f W (Eq. 2.7 on the axle's "
               "absolute motion: %.0f W); %.4f L, %.3f L/100 km; a year of 2,207 h: %.0f MJ, %.0f L\n",
               s.trip.damper_w, s.trip.tire_w, s.trip.tire_eq27_w, s.trip_cost.diesel_l, s.trip_cost.l_per_100km,
               s.annual.energy_mj_per_year, s.annual.diesel_l_per_year);
  // Concrete of every panel length together, weighted by the time measured on each, as the report's
  // tables and bench_dynamic compare it with bituminous.
  double concrete_w_segments = 0, concrete_segments = 0;
  const GroupSpectra* bituminous = nullptr;
  for (const GroupSpectra& g : s.groups) {
    std::fprintf(stderr, "  %-18s dampers %7.1f W  tires %7.1f W", g.name.c_str(), g.power.damper_w, g.power.tire_w);
    if (g.joint.found) {
      std::fprintf(stderr, "  joint line %.2f Hz, panel %.2f m (%.1f sigma)", g.joint_hz, g.joint.panel_m, g.joint.significance);
    } else if (g.expected_panel_m > 0) {
      std::fprintf(stderr, "  no joint line at %.2f m (%.1f sigma)", g.expected_panel_m, g.joint.significance);
    }
    std::fprintf(stderr, "\n");
    if (g.name.rfind("concrete", 0) == 0) {
      concrete_w_segments += g.power.damper_w * static_cast<double>(g.power.segments);
      concrete_segments += static_cast<double>(g.power.segments);
    }
    if (g.name == "bituminous") bituminous = &g;
  }
  if (concrete_segments > 0 && bituminous && bituminous->power.damper_w > 0) {
    std::fprintf(stderr,
                 "analyze: concrete / bituminous damper power %.2f (report: %.2f Mainline Table 6.5, %.2f TH 10 / TH 66 Table 6.6)\n",
                 concrete_w_segments / concrete_segments / bituminous->power.damper_w, kReportMainlineRatio, kReportHighwayRatio);
  }
}

}  // namespace roadload::cli

namespace roadload::cli {

void print_vibration_truth(const VibrationAnalysis& va, const std::vector<CellDef>& cells, const Truth& truth) {
  struct Tally {
    double worst = 0, est = 0, truth = 0;
    std::string worst_cell;
  };
  Tally damper, tire;
  std::size_t n = 0;
  const auto add = [](Tally& t, const std::string& cell, double est, double tru) {
    t.est += est;
    t.truth += tru;
    if (tru > 0 && std::abs(est / tru - 1) > std::abs(t.worst)) {
      t.worst = est / tru - 1;
      t.worst_cell = cell;
    }
  };
  const double hop_s = static_cast<double>(spectra::hop(va.suspension().welch())) / va.suspension().welch().fs_hz;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const DynamicPower p = va.cell_power(c);
    const auto d = truth.damper_w.find(cells[c].id);
    const auto t = truth.tire_w.find(cells[c].id);
    const auto time = truth.time_s.find(cells[c].id);
    if (d == truth.damper_w.end() || t == truth.tire_w.end() || time == truth.time_s.end()) continue;
    // A cell counts when the spectra cover 90 % of its time (none in a sensor's warm-up).
    if (p.segments * hop_s < 0.9 * time->second) continue;
    add(damper, cells[c].id, p.damper_w, d->second);
    add(tire, cells[c].id, p.tire_w, t->second);
    ++n;
  }
  if (n == 0) return;
  std::fprintf(stderr,
               "analyze: against the truth over %zu cells: dampers %+.1f %% (worst cell %s %+.1f %%), "
               "tires %+.1f %% (worst cell %s %+.1f %%)\n",
               n, 100 * (damper.est / damper.truth - 1), damper.worst_cell.c_str(), 100 * damper.worst,
               100 * (tire.est / tire.truth - 1), tire.worst_cell.c_str(), 100 * tire.worst);
}

}  // namespace roadload::cli
