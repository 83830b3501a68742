#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "roadload/db/database.hpp"
#include "roadload/fleet/network.hpp"
#include "roadload/fleet/schema.hpp"
#include "roadload/identification.hpp"
#include "roadload/numbers.hpp"

namespace roadload::fleet {
namespace {

constexpr double kDaysPerYear = 365;

// One drive's result on one section, as the database holds it.
struct Cell {
  std::size_t section = 0;
  std::string drive, truck;
  double crr = NAN, crr_sigma = NAN, speed_mps = NAN, rolling_l = NAN, dynamic_l = NAN, dynamic_l_per_100km = NAN;
  double crr_tire = NAN, crr_tire_sigma = NAN;  // less the dynamic losses, where accelerometers measured them
  bool no_static = false;                       // a force-balance CRR whose dynamic losses are unknown
  std::string reason;
};

// A filter whose innovations are smaller than it predicts (mean NIS below 1) is cautious, not
// wrong: its estimate stands, its sigma is too wide, and the model fits the cells' spread itself.
// A reason names its side of the band; one stored by an older roadload gives only the mean, rounded.
bool overdispersed(const std::string& part) {
  if (!part.starts_with(kNisInconsistent)) return false;
  if (part.find(kNisBelowBand) != std::string::npos) return true;
  if (part.find(kNisAboveBand) != std::string::npos) return false;
  return std::strtod(part.c_str() + kNisInconsistent.size(), nullptr) < 1.0;
}

// Why a cell is not evidence of its section's CRR, or empty when it is. A cell withheld only for
// its width is evidence (the model weighs it); one the model did not fit (the filter's
// consistency, the force balance, the road's placement, no wind) is not: its number may be wrong,
// not merely wide.
std::string exclusion(const Cell& c) {
  if (c.no_static) return "no static CRR: too few samples for the cell's spectra";
  if (!(c.crr_sigma > 0) || !std::isfinite(c.crr) || !std::isfinite(c.speed_mps)) return "no CRR estimate";
  std::string reason = c.reason;
  const std::string prefix = "CRR not identified: ";
  if (reason.rfind(prefix, 0) == 0) reason = reason.substr(prefix.size());
  std::size_t at = 0;
  while (at < reason.size()) {
    const std::size_t end = std::min(reason.find("; ", at), reason.size());
    const std::string part = reason.substr(at, end - at);
    if (part.rfind("its uncertainty", 0) != 0 && !overdispersed(part)) return part.substr(0, part.find(':'));
    at = end + 2;
  }
  return {};
}

std::vector<NetworkSection> read_sections(db::Database& db, std::map<std::string, std::size_t>& index) {
  std::vector<NetworkSection> out;
  for (const db::Row& r :
       db.query("SELECT s.section_key, r.name, s.route_hash, s.cell, s.surface, s.direction, s.start_m, s.end_m, s.start_lat_deg, "
                "s.start_lon_deg, s.end_lat_deg, s.end_lon_deg FROM sections s JOIN routes r ON r.route_hash = s.route_hash")) {
    NetworkSection s;
    s.key = db::text(r[0]), s.route = db::text(r[1]), s.route_hash = db::text(r[2]), s.cell = db::text(r[3]);
    s.surface = db::text(r[4]), s.direction = db::text(r[5]);
    s.start_m = db::number(r[6]).value_or(NAN), s.end_m = db::number(r[7]).value_or(NAN);
    const auto lat0 = db::number(r[8]), lon0 = db::number(r[9]), lat1 = db::number(r[10]), lon1 = db::number(r[11]);
    s.placed = lat0 && lon0 && lat1 && lon1;
    if (s.placed) s.start_lat = *lat0, s.start_lon = *lon0, s.end_lat = *lat1, s.end_lon = *lon1;
    out.push_back(s);
  }
  // The same order from any database: by road, then along it.
  std::sort(out.begin(), out.end(), [](const NetworkSection& a, const NetworkSection& b) {
    return std::tie(a.route, a.route_hash, a.start_m, a.cell) < std::tie(b.route, b.route_hash, b.start_m, b.cell);
  });
  for (std::size_t i = 0; i < out.size(); ++i) index[out[i].key] = i;
  return out;
}

std::vector<Cell> read_cells(db::Database& db, const std::map<std::string, std::size_t>& index) {
  std::vector<Cell> out;
  for (const db::Row& r : db.query("SELECT x.section_key, x.drive_key, d.vehicle_key, x.crr, x.crr_sigma, x.speed_mps, x.rolling_l, "
                                   "x.dynamic_l, x.dynamic_l_per_100km, x.reason, x.crr_tire, x.crr_tire_lo, x.crr_tire_hi FROM "
                                   "section_results x JOIN drives d ON "
                                   "d.drive_key = x.drive_key")) {
    Cell c;
    c.section = index.at(db::text(r[0]));
    c.drive = db::text(r[1]), c.truck = db::text(r[2]);
    c.crr = db::number(r[3]).value_or(NAN), c.crr_sigma = db::number(r[4]).value_or(NAN);
    c.speed_mps = db::number(r[5]).value_or(NAN), c.rolling_l = db::number(r[6]).value_or(NAN);
    c.dynamic_l = db::number(r[7]).value_or(NAN), c.dynamic_l_per_100km = db::number(r[8]).value_or(NAN);
    c.reason = db::text(r[9]);
    c.crr_tire = db::number(r[10]).value_or(NAN);
    c.crr_tire_sigma = (db::number(r[12]).value_or(NAN) - db::number(r[11]).value_or(NAN)) / (2 * kZ90);
    out.push_back(c);
  }
  std::sort(out.begin(), out.end(),
            [](const Cell& a, const Cell& b) { return std::tie(a.section, a.drive) < std::tie(b.section, b.drive); });
  return out;
}

// The static CRR (the tires' on the pavement, the dynamic losses apart: the network reports those
// on their own) where the drives measured their dynamic losses on nearly every cell (a cell the
// drive only touched may have too few samples for its spectra; it is then left out, counted);
// else the force balance's CRR for all, rather than two quantities mixed on one section.
bool static_crr(std::vector<Cell>& cells) {
  constexpr double kNeeded = 0.9;
  const auto with = std::count_if(cells.begin(), cells.end(), [](const Cell& c) {
    return std::isfinite(c.crr) && std::isfinite(c.crr_tire) && c.crr_tire_sigma > 0;
  });
  const auto all = std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return std::isfinite(c.crr); });
  if (all == 0 || static_cast<double>(with) < kNeeded * static_cast<double>(all)) return false;
  for (Cell& c : cells) {
    if (!std::isfinite(c.crr)) continue;
    c.no_static = !(std::isfinite(c.crr_tire) && c.crr_tire_sigma > 0);
    c.crr = c.crr_tire, c.crr_sigma = c.crr_tire_sigma;
  }
  return true;
}

// Indices of `keys` in sorted order: the same numbering from any database.
std::map<std::string, std::size_t> numbering(const std::set<std::string>& keys) {
  std::map<std::string, std::size_t> out;
  for (const std::string& k : keys) out.emplace(k, out.size());
  return out;
}

// What the cells used say beside CRR: how many drives and trucks, their speed, the dynamic
// rolling resistance, and the fuel of a pass at the section's fitted CRR.
void describe(NetworkSection& s, const std::vector<const Cell*>& used, const NetworkOptions& o) {
  std::set<std::string> drives, trucks;
  double speed = 0, rolling = 0, dynamic = 0, dyn_sum = 0, dyn_sq = 0;
  int dyn_n = 0;
  for (const Cell* c : used) {
    drives.insert(c->drive), trucks.insert(c->truck);
    speed += c->speed_mps;
    rolling += std::isfinite(c->rolling_l) ? c->rolling_l * s.crr.crr / c->crr : 0;
    dynamic += std::isfinite(c->dynamic_l) ? c->dynamic_l : 0;
    if (std::isfinite(c->dynamic_l_per_100km))
      dyn_sum += c->dynamic_l_per_100km, dyn_sq += std::pow(c->dynamic_l_per_100km, 2), ++dyn_n;
  }
  const double n = static_cast<double>(used.size());
  s.drives = static_cast<int>(drives.size()), s.trucks = static_cast<int>(trucks.size()), s.cells = static_cast<int>(used.size());
  if (used.empty()) {
    s.speed_mps = s.dynamic_l_per_100km = s.dynamic_l_per_100km_se = NAN;
    s.rolling_l_per_pass = s.dynamic_l_per_pass = s.rolling_l_per_year = s.dynamic_l_per_year = NAN;
    return;
  }
  s.speed_mps = speed / n;
  s.rolling_l_per_pass = rolling / n;
  s.dynamic_l_per_pass = dynamic / n;
  if (dyn_n > 0) {
    s.dynamic_l_per_100km = dyn_sum / dyn_n;
    s.dynamic_l_per_100km_se = dyn_n > 1 ? std::sqrt(std::max(dyn_sq / dyn_n - std::pow(s.dynamic_l_per_100km, 2), 0.0) / (dyn_n - 1))
                                         : NAN;
  }
  s.rolling_l_per_year = s.rolling_l_per_pass * o.trucks_per_day * kDaysPerYear;
  s.dynamic_l_per_year = s.dynamic_l_per_pass * o.trucks_per_day * kDaysPerYear;
}

// The same model with one column per section and speed band: a band's figure is as precise
// as that band's drives make it, the shared errors still fitted from every drive.
std::vector<NetworkBand> fit_bands(const std::vector<const Cell*>& used, const std::map<std::string, std::size_t>& drive_no,
                                   const std::map<std::string, std::size_t>& truck_no, const NetworkOptions& o) {
  std::map<std::pair<std::size_t, long>, std::size_t> column;
  for (const Cell* c : used) column.emplace(std::pair{c->section, std::lround(std::floor(c->speed_mps / o.speed_band_mps))}, 0);
  std::size_t n = 0;
  for (auto& [key, index] : column) index = n++;
  std::vector<network::SectionObservation> obs;
  std::vector<std::set<std::string>> drives(n), trucks(n);
  for (const Cell* c : used) {
    const std::size_t k = column.at({c->section, std::lround(std::floor(c->speed_mps / o.speed_band_mps))});
    obs.push_back({k, drive_no.at(c->drive), truck_no.at(c->truck), c->crr, c->crr_sigma, c->speed_mps});
    drives[k].insert(c->drive), trucks[k].insert(c->truck);
  }
  const network::SectionNetworkFit fit = network::fit_section_network(obs, n, drive_no.size(), truck_no.size());
  std::vector<NetworkBand> out;
  for (const auto& [key, k] : column) {
    out.push_back({key.first, static_cast<double>(key.second) * o.speed_band_mps,
                   static_cast<double>(key.second + 1) * o.speed_band_mps, static_cast<int>(drives[k].size()),
                   static_cast<int>(trucks[k].size()), fit.sections[k]});
  }
  return out;
}

}  // namespace

// Long because it is the view's one pass: read, number, choose the evidence, fit, describe.
NetworkView network_view(const std::string& db_url, const NetworkOptions& options) {
  const auto db = db::open_database(db_url, db::Open::existing);
  migrate(*db);
  NetworkView v;
  v.options = options;
  std::map<std::string, std::size_t> section_index;
  v.sections = read_sections(*db, section_index);
  std::vector<Cell> cells = read_cells(*db, section_index);
  v.static_crr = static_crr(cells);
  std::set<std::string> drive_keys, truck_keys;
  std::vector<const Cell*> used;
  for (const Cell& c : cells) {
    drive_keys.insert(c.drive);
    if (!std::isfinite(c.crr) && !c.no_static) continue;  // a section of the route this drive did not reach
    const std::string why = exclusion(c);
    if (!why.empty()) {
      ++v.excluded[why], ++v.cells_excluded;
      continue;
    }
    used.push_back(&c);
    truck_keys.insert(c.truck);
  }
  v.drives = static_cast<int>(drive_keys.size());
  v.cells_used = static_cast<int>(used.size());
  const auto drive_no = numbering(drive_keys), truck_no = numbering(truck_keys);
  std::vector<network::SectionObservation> obs;
  for (const Cell* c : used)
    obs.push_back({c->section, drive_no.at(c->drive), truck_no.at(c->truck), c->crr, c->crr_sigma, c->speed_mps});
  v.fit = network::fit_section_network(obs, v.sections.size(), drive_no.size(), truck_no.size());
  std::vector<std::vector<const Cell*>> by_section(v.sections.size());
  for (const Cell* c : used) by_section[c->section].push_back(c);
  for (std::size_t s = 0; s < v.sections.size(); ++s) {
    v.sections[s].crr = v.fit.sections[s];
    describe(v.sections[s], by_section[s], options);
  }
  std::map<std::string, int> truck_drives;
  std::set<std::pair<std::string, std::string>> seen;
  for (const Cell* c : used) {
    if (seen.insert({c->truck, c->drive}).second) ++truck_drives[c->truck];
  }
  for (const db::Row& r : db->query("SELECT vehicle_key, vin, name FROM vehicles")) {
    const auto t = truck_no.find(db::text(r[0]));
    if (t == truck_no.end()) continue;
    v.trucks.push_back({t->first, db::text(r[1]), db::text(r[2]), truck_drives[t->first], v.fit.trucks[t->second]});
  }
  std::sort(v.trucks.begin(), v.trucks.end(), [](const NetworkTruck& a, const NetworkTruck& b) { return a.key < b.key; });
  v.bands = fit_bands(used, drive_no, truck_no, options);
  return v;
}

}  // namespace roadload::fleet
