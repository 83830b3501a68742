#include "roadload/report/report_figures.hpp"

#include <cmath>
#include <limits>
#include <set>

#include "roadload/fuel_breakdown.hpp"

namespace roadload::report {
namespace {

using results::NumberTable;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::vector<double> column(const NumberTable& t, const std::string& name) {
  std::vector<double> v = t.values(name);
  v.resize(t.rows(), kNan);
  return v;
}

template <typename Map>
std::vector<double> by_cell(const std::vector<std::string>& ids, const Map& m) {
  std::vector<double> v;
  for (const std::string& id : ids) {
    const auto it = m.find(id);
    v.push_back(it == m.end() ? kNan : it->second);
  }
  return v;
}

FuelUse use(std::size_t i) { return static_cast<FuelUse>(i); }

}  // namespace

const results::JsonValue* pavement_groups(const results::JsonValue& trip) {
  const results::JsonValue* dynamic = trip.find("dynamic_rolling");
  return dynamic ? dynamic->find("groups") : nullptr;
}

std::vector<std::string> cell_ids(const NumberTable& cells) {
  std::vector<std::string> ids;
  const std::size_t c = *cells.column("cell");
  for (std::size_t r = 0; r < cells.rows(); ++r) ids.push_back(cells.text(r, c));
  return ids;
}

std::vector<std::string> axle_names(const NumberTable& cells) {
  std::vector<std::string> axles;
  for (const std::string& c : cells.columns()) {
    if (c.starts_with("fz_") && c.ends_with("_mean_n")) axles.push_back(c.substr(3, c.size() - 3 - 7));
  }
  return axles;
}

Figure crr_per_cell(const NumberTable& cells, const results::Truth* truth) {
  Chart c{"crr-per-cell",
          {"pavement cell", false, false},
          {"coefficient of rolling resistance", false, false},
          cell_ids(cells),
          false,
          {},
          {}};
  c.series.push_back({"force balance, 90 % interval",
                      Series::Style::points,
                      {},
                      column(cells, "crr"),
                      column(cells, "crr_lo"),
                      column(cells, "crr_hi")});
  const bool tires = cells.column("crr_tire").has_value();
  if (tires) {
    c.series.push_back({"the tires' own, 90 % interval",
                        Series::Style::points,
                        {},
                        column(cells, "crr_tire"),
                        column(cells, "crr_tire_lo"),
                        column(cells, "crr_tire_hi")});
  }
  if (truth)
    c.series.push_back({"simulated truth (the tires')", Series::Style::points, {}, by_cell(c.categories, truth->crr), {}, {}});
  return {std::move(c), tires ? "CRR per cell with its 90 % interval, in route order (seed report Figure 6.2, Table 6.3): the force "
                                "balance's, all that resists rolling, and the tires' own, less what the dampers and tires dissipate "
                                "of the road's roughness (the accelerometers' dynamic rolling resistance)."
                              : "CRR per cell with its 90 % interval, in route order (seed report Figure 6.2, Table 6.3)."};
}

Figure rolling_fuel_per_cell(const NumberTable& cells) {
  Chart c{"rolling-fuel-per-cell", {"pavement cell", false, false}, {"diesel (L)", false, true}, cell_ids(cells), false, {}, {}};
  c.series.push_back({"rolling resistance", Series::Style::bars, {}, column(cells, "rolling_l"), {}, {}});
  if (cells.column("dynamic_l"))
    c.series.push_back({"of it dynamic (dampers and tires)", Series::Style::bars, {}, column(cells, "dynamic_l"), {}, {}});
  return {std::move(c),
          "Fuel spent on rolling resistance in each cell, and the part the accelerometers attribute to the dampers "
          "and tires (seed report Figure 6.3)."};
}

Figure fuel_breakdown_per_cell(const NumberTable& cells) {
  Chart c{"fuel-breakdown-per-cell", {"pavement cell", false, false}, {"diesel (L)", false, true}, cell_ids(cells), true, {}, {}};
  for (std::size_t i = 0; i < kFuelUseCount; ++i) {
    c.series.push_back({to_string(use(i)), Series::Style::bars, {}, column(cells, std::string(to_string(use(i))) + "_l"), {}, {}});
  }
  return {std::move(c),
          "Where each cell's fuel went, by force (engine and driveline losses, accessories, aero, rolling, grade, "
          "acceleration, braking)."};
}

Figure trip_fuel_breakdown(const results::JsonValue& trip, const results::Truth* truth) {
  Chart c{"trip-fuel-breakdown", {"", false, false}, {"diesel (L)", false, true}, {}, false, {}, {}};
  Series est{"estimate", Series::Style::bars, {}, {}, {}, {}};
  Series tru{"simulated truth", Series::Style::bars, {}, {}, {}, {}};
  const double mj_per_l = trip.number_at("fuel.diesel_energy_mj_per_l").value_or(kDieselEnergy_jpl / 1e6);
  for (std::size_t i = 0; i < kFuelUseCount; ++i) {
    const std::string name = to_string(use(i));
    c.categories.push_back(name);
    est.y.push_back(trip.number_at("fuel." + name + "_l").value_or(kNan));
    if (truth) {
      const auto it = truth->energy_j.find(name + "_j");
      tru.y.push_back(it == truth->energy_j.end() ? kNan : it->second / (mj_per_l * 1e6));
    }
  }
  c.series.push_back(std::move(est));
  if (truth && !truth->energy_j.empty()) c.series.push_back(std::move(tru));
  return {std::move(c), "The trip's fuel broken down by force (seed report Figures 2.2, 6.4 and 6.5)."};
}

// The axles' static loads differ by tens of kN and the rear four carry nearly the same, so their
// means would sit on one another; what a pavement changes is the dynamic part, drawn here side by
// side per cell. The means are in the table beneath (contact_table).
std::optional<Figure> contact_forces(const NumberTable& cells) {
  const std::vector<std::string> axles = axle_names(cells);
  if (axles.empty()) return std::nullopt;
  Chart c{"contact-forces",
          {"pavement cell", false, false},
          {"dynamic contact force, standard deviation (kN)", false, true},
          cell_ids(cells),
          false,
          {},
          {}};
  for (const std::string& a : axles) {
    Series s{a, Series::Style::bars, {}, column(cells, "fz_" + a + "_dynamic_std_n"), {}, {}};
    for (double& v : s.y) v /= 1000;
    c.series.push_back(std::move(s));
  }
  return Figure{std::move(c),
                "The dynamic part of each axle's tire contact force from the accelerometers (Eq. 2.1): its standard "
                "deviation in each cell, the load the pavement's roughness adds and takes away (seed report Figure 6.1 "
                "draws the mean and standard deviation; the means are in the table)."};
}

std::optional<Figure> dynamic_power_per_cell(const NumberTable& cells, const results::Truth* truth) {
  if (!cells.column("damper_power_w")) return std::nullopt;
  Chart c{"dynamic-power-per-cell", {"pavement cell", false, false}, {"power (W)", false, true}, cell_ids(cells), false, {}, {}};
  c.series.push_back({"dampers", Series::Style::bars, {}, column(cells, "damper_power_w"), {}, {}});
  c.series.push_back({"tires", Series::Style::bars, {}, column(cells, "tire_power_w"), {}, {}});
  if (truth && !truth->damper_w.empty()) {
    c.series.push_back({"dampers, truth", Series::Style::points, {}, by_cell(c.categories, truth->damper_w), {}, {}});
    c.series.push_back({"tires, truth", Series::Style::points, {}, by_cell(c.categories, truth->tire_w), {}, {}});
  }
  return Figure{std::move(c),
                "Power the dampers and tires dissipate in each cell: the dynamic rolling resistance (Eq. 2.7-2.8; "
                "seed report Figure 6.9)."};
}

Figure spectrum(const results::Spectrum& s, const results::JsonValue& trip) {
  const bool spatial = s.x_name == "cycles_per_m";
  Chart c{"psd-" + s.group,
          {spatial ? "wavenumber (cycles/m)" : "frequency (Hz)", true, false},
          {spatial ? "PSD ((m/s\u00b2)\u00b2 per cycle/m)" : "PSD ((m/s\u00b2)\u00b2/Hz)", true, false},
          {},
          false,
          {},
          {}};
  for (std::size_t k = 0; k < s.sensors.size(); ++k) {
    c.series.push_back({s.sensors[k], Series::Style::line, s.x, s.psd[k], {}, {}});
  }
  std::string caption = "Power spectral density of each accelerometer";
  const results::JsonValue* groups = pavement_groups(trip);
  const results::JsonValue* group = nullptr;
  for (std::size_t i = 0; groups && i < groups->items().size(); ++i) {
    const results::JsonValue& g = groups->items()[i];
    if (g.find("name") && g.find("name")->string() == s.group) group = &g;
  }
  if (group) {
    std::set<std::string> labelled;
    if (const results::JsonValue* modes = group->find("modes")) {
      for (const results::JsonValue& sensor : modes->items()) {
        for (const results::JsonValue& m : sensor.items()) {
          const std::string label = m.find("label") ? m.find("label")->string() : "";
          const double f = m.number_at("freq_hz").value_or(kNan);
          if (label.empty() || !labelled.insert(label).second) continue;
          c.markers.push_back({f, label + " " + format_number(f, 3) + " Hz", false});
        }
      }
    }
    const double joint_hz = group->number_at("joint_line.freq_hz").value_or(kNan);
    const results::JsonValue* found = group->find("joint_line") ? group->find("joint_line")->find("found") : nullptr;
    if (found && found->boolean() && joint_hz > 0) {
      const double panel = group->number_at("joint_line.panel_m").value_or(kNan);
      for (int k = 1; k <= 3; ++k)
        c.markers.push_back({k * joint_hz, k == 1 ? "joints, " + format_number(panel, 3) + " m panels" : "", true});
    }
    caption += " on " + s.group + ", with the vibration modes found and the joint line where one was detected";
  } else {
    caption += s.group == "trip" ? " over the whole trip" : " on " + s.group;
  }
  return {std::move(c), caption + " (seed report Figures 6.6-6.8, 6.10, 6.11)."};
}

}  // namespace roadload::report
