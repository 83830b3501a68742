#include "roadload/results/results_files.hpp"

#include <cmath>
#include <fstream>

#include "roadload/recording/writer.hpp"
#include "roadload/results/json.hpp"
#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/tire_crr.hpp"

namespace roadload::results {
namespace {

constexpr std::size_t kUses = kFuelUseCount;

FuelUse use(std::size_t i) { return static_cast<FuelUse>(i); }

}  // namespace

std::vector<CellPlace> cell_places(const RouteGeometry& route, const std::vector<CellSpan>& spans,
                                   const std::vector<std::string>& surfaces) {
  std::vector<CellPlace> out;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    out.push_back({i < surfaces.size() ? surfaces[i] : std::string(), route.at(spans[i].start_m), route.at(spans[i].end_m)});
  }
  return out;
}

std::optional<ParseError> write_cells_csv(const std::string& path, const std::vector<CellResult>& cells,
                                          const std::vector<std::string>& axle_names, const VibrationAnalysis* vibration,
                                          const std::vector<CellPlace>& places, const Provenance* provenance) {
  auto csv = recording::OutputFile::create(path);
  if (!csv) return csv.error();
  std::string header = "cell,start_m,end_m,samples,crr,crr_lo,crr_hi,crr_sigma,identified,speed_mps,roll_force_n,fuel_l";
  for (std::size_t i = 0; i < kUses; ++i) header += std::string(",") + to_string(use(i)) + "_l";
  for (const std::string& a : axle_names) header += ",fz_" + a + "_mean_n,fz_" + a + "_std_n,fz_" + a + "_dynamic_std_n";
  if (vibration) {
    header += ",damper_power_w,tire_power_w,tire_eq27_power_w,dynamic_energy_j,dynamic_l,dynamic_l_per_100km";
    header += ",crr_tire,crr_tire_lo,crr_tire_hi";
  }
  csv.value().write(header +
                    ",surface,start_lat_deg,start_lon_deg,end_lat_deg,end_lon_deg,recording_id,vin,vehicle_hash,route_hash,"
                    "drive_start_utc,reason\n");
  const Provenance none;
  const Provenance& from = provenance ? *provenance : none;
  recording::LineBuilder line;
  const double nan = std::nan("");
  for (std::size_t row = 0; row < cells.size(); ++row) {
    const CellResult& c = cells[row];
    line.clear();
    line.field(c.id).sep().num(c.start_m, 1).sep().num(c.end_m, 1).sep().num(static_cast<std::int64_t>(c.samples)).sep();
    const bool have = c.samples > 0;
    line.num(have ? c.crr : nan, 6).sep().num(have ? c.crr_lo : nan, 6).sep().num(have ? c.crr_hi : nan, 6).sep();
    line.num(have ? c.crr_sigma : nan, 6).sep().num(std::int64_t{c.identified ? 1 : 0}).sep();
    line.num(have ? c.speed_mps : nan, 3).sep().num(have ? c.roll_force_n : nan, 1).sep();
    const bool driven = c.fuel.distance_m > 0;
    line.num(driven ? c.fuel.fuel_l : nan, 5).sep();
    for (std::size_t i = 0; i < kUses; ++i) line.num(driven ? c.fuel.liters(use(i)) : nan, 5).sep();
    for (std::size_t a = 0; a < axle_names.size(); ++a) {
      const bool have_fz = a < c.contact.size() && c.contact[a].fz.count > 1;
      line.num(have_fz ? c.contact[a].fz.mean_n : nan, 1).sep().num(have_fz ? c.contact[a].fz.std_n : nan, 1).sep();
      line.num(have_fz ? c.contact[a].dynamic.std_n : nan, 1).sep();
    }
    if (vibration) {
      const DynamicPower p = vibration->cell_power(row);
      const bool measured = p.segments > 0;
      const spectra::StretchCost cost = spectra::stretch_cost(
          p.total_w(), c.fuel.time_s, c.fuel.time_s > 0 ? c.fuel.distance_m / c.fuel.time_s : 0.0, kDieselEnergy_jpl);
      line.num(measured ? p.damper_w : nan, 2)
          .sep()
          .num(measured ? p.tire_w : nan, 2)
          .sep()
          .num(measured ? p.tire_eq27_w : nan, 2)
          .sep();
      line.num(measured && driven ? cost.energy_j : nan, 1).sep().num(measured && driven ? cost.diesel_l : nan, 6).sep();
      line.num(measured && driven ? cost.l_per_100km : nan, 4).sep();
      const std::optional<TireCrr> tire = measured ? tire_crr(c, p.total_w()) : std::nullopt;
      line.num(tire ? tire->crr : nan, 6).sep().num(tire ? tire->lo : nan, 6).sep().num(tire ? tire->hi : nan, 6).sep();
    }
    const CellPlace* place = row < places.size() ? &places[row] : nullptr;
    line.field(place ? place->surface : std::string()).sep();
    line.num(place ? place->start.lat_deg : nan, 7).sep().num(place ? place->start.lon_deg : nan, 7).sep();
    line.num(place ? place->end.lat_deg : nan, 7).sep().num(place ? place->end.lon_deg : nan, 7).sep();
    for (const std::string* f : {&from.recording_id, &from.vin, &from.vehicle_hash, &from.route_hash, &from.drive_start_utc})
      line.field(*f).sep();
    line.field(c.reason);
    csv.value().write(line.finish());
  }
  return csv.value().close();
}

std::optional<ParseError> write_pavements_csv(const std::string& path, const std::vector<PavementResult>& pavements) {
  auto csv = recording::OutputFile::create(path);
  if (!csv) return csv.error();
  csv.value().write(
      "pavement,cells,length_m,samples,crr,crr_lo,crr_hi,crr_sigma,identified,speed_mps,rolling_l,distance_m,"
      "rolling_l_per_100km,reason\n");
  recording::LineBuilder line;
  const double nan = std::nan("");
  for (const PavementResult& p : pavements) {
    const CellResult& c = p.crr;
    const bool have = c.samples > 0 && c.crr_sigma > 0;
    line.clear();
    line.field(c.id).sep().num(static_cast<std::int64_t>(p.cells)).sep().num(c.end_m - c.start_m, 1).sep();
    line.num(static_cast<std::int64_t>(c.samples)).sep();
    line.num(have ? c.crr : nan, 6).sep().num(have ? c.crr_lo : nan, 6).sep().num(have ? c.crr_hi : nan, 6).sep();
    line.num(have ? c.crr_sigma : nan, 6).sep().num(std::int64_t{c.identified ? 1 : 0}).sep();
    line.num(have ? c.speed_mps : nan, 3).sep().num(p.rolling_l, 5).sep().num(p.distance_m, 1).sep();
    line.num(p.distance_m > 0 ? p.rolling_l_per_100km() : nan, 4).sep().field(c.reason);
    csv.value().write(line.finish());
  }
  return csv.value().close();
}

std::string pavements_json(const std::vector<PavementResult>& pavements) {
  const auto n = [](double v) { return json_number(v); };
  std::string j = "  \"pavements\": [";
  for (std::size_t i = 0; i < pavements.size(); ++i) {
    const PavementResult& p = pavements[i];
    const CellResult& c = p.crr;
    const bool have = c.samples > 0 && c.crr_sigma > 0;
    j += std::string(i ? "," : "") + "\n    {\"pavement\": " + json_quote(c.id) + ", \"cells\": " + std::to_string(p.cells) +
         ", \"length_m\": " + n(c.end_m - c.start_m) + ", \"samples\": " + std::to_string(c.samples);
    j += ", \"crr\": " + (have ? n(c.crr) : "null") + ", \"crr_lo\": " + (have ? n(c.crr_lo) : "null") +
         ", \"crr_hi\": " + (have ? n(c.crr_hi) : "null") + ", \"crr_identified\": " + (c.identified ? "true" : "false");
    j += ", \"rolling_l_per_100km\": " + (p.distance_m > 0 ? n(p.rolling_l_per_100km()) : "null") +
         ", \"distance_m\": " + n(p.distance_m) + ", \"reason\": " + json_quote(c.reason) + "}";
  }
  return j + (pavements.empty() ? "]" : "\n  ]");
}

std::optional<ParseError> write_trip_json(const std::string& path, const TripResult& trip, const std::string& extra) {
  const auto n = [](double v) { return json_number(v); };
  std::ofstream json(path);
  json << "{\n  \"crr\": " << n(trip.crr) << ",\n  \"crr_sigma\": " << n(trip.crr_sigma)
       << ",\n  \"crr_identified\": " << (trip.identified ? "true" : "false") << ",\n  \"not_identified\": [";
  for (std::size_t i = 0; i < trip.not_identified.size(); ++i) json << (i ? ", " : "") << json_quote(trip.not_identified[i]);
  json << "],\n  \"cda_m2\": " << n(trip.cda_m2) << ",\n  \"mass_kg\": " << n(trip.mass_kg)
       << ",\n  \"mass_sigma_kg\": " << n(trip.mass_sigma_kg) << ",\n  \"ticks\": " << trip.ticks
       << ",\n  \"usable_ticks\": " << trip.usable_ticks << ",\n  \"coasting_ticks\": " << trip.coasting_ticks
       << ",\n  \"unusable\": {";
  for (std::size_t i = 1; i < trip.unusable.size(); ++i) {
    json << (i > 1 ? ", " : "") << json_quote(to_string(static_cast<Unusable>(i))) << ": " << trip.unusable[i];
  }
  json << "},\n  \"gnss_used\": " << trip.gnss_used << ",\n  \"gnss_off_route\": " << trip.gnss_off_route
       << ",\n  \"speed_outliers\": " << trip.filter.outliers << ",\n  \"mean_nis\": " << n(trip.mean_nis)
       << ",\n  \"mean_nis_95\": " << n(1.96 * trip.mean_nis_se) << ",\n  \"torque_bias_sigma_nm\": " << n(trip.torque_bias_sigma_nm)
       << ",\n  \"fuel\": {\n    \"measured_l\": " << n(trip.fuel.fuel_l) << ",\n    \"unsplit_l\": " << n(trip.fuel.unsplit_l)
       << ",\n    \"diesel_energy_mj_per_l\": " << n(kDieselEnergy_jpl / 1e6) << ",\n    \"closure\": " << n(trip.fuel.closure())
       << ",\n    \"unexplained_work_j\": " << n(trip.fuel.unexplained_j()) << ",\n    \"wheel_work_j\": " << n(trip.fuel.wheel_j)
       << ",\n    \"distance_m\": " << n(trip.fuel.distance_m) << ",\n    \"ticks_without_fuel_rate\": " << trip.no_fuel_rate;
  for (std::size_t i = 0; i < kUses; ++i) json << ",\n    \"" << to_string(use(i)) << "_l\": " << n(trip.fuel.liters(use(i)));
  json << "\n  }";
  if (!extra.empty()) json << ",\n" << extra;
  json << "\n}\n";
  json.close();
  if (!json) return ParseError{path, 0, "file", "could not be written"};
  return std::nullopt;
}

}  // namespace roadload::results
