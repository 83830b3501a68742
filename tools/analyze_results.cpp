#include "analyze_results.hpp"

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string_view>

#include "roadload/recording/csv.hpp"
#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/toml_fields.hpp"

namespace roadload::cli {
namespace {

constexpr std::size_t kUses = kFuelUseCount;

FuelUse use(std::size_t i) { return static_cast<FuelUse>(i); }

std::optional<double> truth_energy_j(const Truth& t, FuelUse u) {
  const auto it = t.energy_j.find(std::string(to_string(u)) + "_j");
  if (it == t.energy_j.end()) return std::nullopt;
  return it->second;
}

const double* true_crr(const Truth* t, const std::string& cell) {
  if (t == nullptr) return nullptr;
  const auto it = t->crr.find(cell);
  return it == t->crr.end() ? nullptr : &it->second;
}

Parsed<Truth> read_truth_cells(const std::string& path) {
  constexpr std::string_view kColumns[] = {"cell", "crr", "damper_power_w", "tire_power_w", "time_s"};
  auto csv = recording::CsvReader::open(path, kColumns);
  if (!csv) return csv.error();
  Truth t;
  std::span<const std::string_view> row;
  for (recording::CsvReader::Status st; (st = csv.value().next(row)) != recording::CsvReader::Status::end;) {
    if (st == recording::CsvReader::Status::bad_row) return *csv.value().error();
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto value = recording::parse_f64(row[i + 1]);
      if (!value) return csv.value().field_error(i + 1, "expected a number");
      v[i] = *value;
    }
    const std::string cell(row[0]);
    t.crr[cell] = v[0];
    t.damper_w[cell] = v[1];
    t.tire_w[cell] = v[2];
    t.time_s[cell] = v[3];
  }
  if (csv.value().error()) return *csv.value().error();
  return t;
}

Parsed<std::map<std::string, double>> read_truth_energy(const std::string& path) {
  std::map<std::string, double> energy;
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const toml::table* section = parsed.value()["fuel_breakdown"].as_table();
  if (section == nullptr) return energy;
  const detail::TomlFields f(path);
  try {
    for (const auto& [key, node] : *section) energy[std::string(key.str())] = f.required_number(*section, key.str(), "fuel_breakdown.");
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
  return energy;
}

}  // namespace

std::optional<ParseError> write_cells_csv(const std::string& path, const std::vector<CellResult>& cells,
                                          const std::vector<std::string>& axle_names, const VibrationAnalysis* vibration) {
  auto csv = recording::OutputFile::create(path);
  if (!csv) return csv.error();
  std::string header = "cell,start_m,end_m,samples,crr,crr_lo,crr_hi,crr_sigma,identified,speed_mps,roll_force_n,fuel_l";
  for (std::size_t i = 0; i < kUses; ++i) header += std::string(",") + to_string(use(i)) + "_l";
  for (const std::string& a : axle_names) header += ",fz_" + a + "_mean_n,fz_" + a + "_std_n,fz_" + a + "_dynamic_std_n";
  if (vibration) header += ",damper_power_w,tire_power_w,tire_eq27_power_w,dynamic_energy_j,dynamic_l,dynamic_l_per_100km";
  csv.value().write(header + ",reason\n");
  recording::LineBuilder line;
  const double nan = std::nan("");
  for (std::size_t row = 0; row < cells.size(); ++row) {
    const CellResult& c = cells[row];
    line.clear();
    line.text(c.id).sep().num(c.start_m, 1).sep().num(c.end_m, 1).sep().num(static_cast<std::int64_t>(c.samples)).sep();
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
      const spectra::StretchCost cost = spectra::stretch_cost(p.total_w(), c.fuel.time_s, c.fuel.time_s > 0 ? c.fuel.distance_m / c.fuel.time_s : 0.0, kDieselEnergy_jpl);
      line.num(measured ? p.damper_w : nan, 2).sep().num(measured ? p.tire_w : nan, 2).sep().num(measured ? p.tire_eq27_w : nan, 2).sep();
      line.num(measured && driven ? cost.energy_j : nan, 1).sep().num(measured && driven ? cost.diesel_l : nan, 6).sep();
      line.num(measured && driven ? cost.l_per_100km : nan, 4).sep();
    }
    line.text(c.reason);
    csv.value().write(line.finish());
  }
  return csv.value().close();
}

std::optional<ParseError> write_trip_json(const std::string& path, const TripResult& trip, const std::string& extra) {
  std::ofstream json(path);
  json << "{\n  \"crr\": " << trip.crr << ",\n  \"crr_sigma\": " << trip.crr_sigma << ",\n  \"crr_identified\": "
       << (trip.identified ? "true" : "false") << ",\n  \"cda_m2\": " << trip.cda_m2 << ",\n  \"ticks\": " << trip.ticks
       << ",\n  \"usable_ticks\": " << trip.usable_ticks << ",\n  \"unusable\": {";
  for (std::size_t i = 1; i < trip.unusable.size(); ++i) {
    json << (i > 1 ? ", " : "") << "\"" << to_string(static_cast<Unusable>(i)) << "\": " << trip.unusable[i];
  }
  json << "},\n  \"gnss_used\": " << trip.gnss_used << ",\n  \"gnss_off_route\": " << trip.gnss_off_route
       << ",\n  \"speed_outliers\": " << trip.filter.outliers << ",\n  \"mean_nis\": " << trip.mean_nis << ",\n  \"mean_nis_95\": " << 1.96 * trip.mean_nis_se
       << ",\n  \"torque_bias_sigma_nm\": " << trip.torque_bias_sigma_nm << ",\n  \"fuel\": {\n    \"measured_l\": "
       << trip.fuel.fuel_l << ",\n    \"unsplit_l\": " << trip.fuel.unsplit_l << ",\n    \"diesel_energy_mj_per_l\": " << kDieselEnergy_jpl / 1e6
       << ",\n    \"closure\": " << trip.fuel.closure() << ",\n    \"distance_m\": " << trip.fuel.distance_m
       << ",\n    \"ticks_without_fuel_rate\": " << trip.no_fuel_rate;
  for (std::size_t i = 0; i < kUses; ++i) json << ",\n    \"" << to_string(use(i)) << "_l\": " << trip.fuel.liters(use(i));
  json << "\n  }";
  if (!extra.empty()) json << ",\n" << extra;
  json << "\n}\n";
  json.close();
  if (!json) return ParseError{path, 0, "file", "could not be written"};
  return std::nullopt;
}

Parsed<Truth> read_truth(const std::string& dir) {
  auto cells = read_truth_cells(dir + "/cells.csv");
  if (!cells) return cells.error();
  Truth t = std::move(cells.value());
  auto energy = read_truth_energy(dir + "/truth.toml");
  if (!energy) return energy.error();
  t.energy_j = std::move(energy.value());
  return t;
}

void print_cells(const std::vector<CellResult>& cells, const Truth* truth) {
  std::printf("%-6s %9s %9s %9s %7s %9s%s\n", "cell", "crr", "crr_lo", "crr_hi", "samples", "roll_l", truth ? "     truth  inside" : "");
  for (const CellResult& c : cells) {
    if (c.samples == 0) {
      std::printf("%-6s %9s %9s %9s %7zu %9s  %s\n", c.id.c_str(), "-", "-", "-", c.samples, "-", c.reason.c_str());
      continue;
    }
    std::printf("%-6s %9.5f %9.5f %9.5f %7zu %9.5f", c.id.c_str(), c.crr, c.crr_lo, c.crr_hi, c.samples, c.fuel.liters(FuelUse::rolling));
    if (const double* t = true_crr(truth, c.id)) std::printf("   %7.5f  %s", *t, *t >= c.crr_lo && *t <= c.crr_hi ? "yes" : "no");
    std::printf("\n");
  }
}

void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth) {
  std::fprintf(stderr, "analyze: trip CRR %.5f +- %.5f (%s), CdA %.2f m^2, %zu of %zu ticks usable, mean NIS %.2f +- %.2f\n",
               trip.crr, trip.crr_sigma, trip.identified ? "identified" : "NOT identified", trip.cda_m2,
               trip.usable_ticks, trip.ticks, trip.mean_nis, 1.96 * trip.mean_nis_se);
  const FuelBreakdown& f = trip.fuel;
  std::fprintf(stderr, "analyze: fuel %.3f L measured (LFE1), %.3f L of it while the engine's torques were unknown; "
               "rows sum to %.3f L (closure %+.2f %%)\n", f.fuel_l, f.unsplit_l, f.sum_l(), 100.0 * f.closure());
  for (std::size_t i = 0; i < kUses; ++i) {
    std::fprintf(stderr, "  %-13s %8.4f L %6.1f %%", to_string(use(i)), f.liters(use(i)),
                 f.fuel_l > 0 ? 100.0 * f.liters(use(i)) / f.fuel_l : 0.0);
    const auto t = truth ? truth_energy_j(*truth, use(i)) : std::nullopt;
    if (t) std::fprintf(stderr, "   truth %8.4f L", *t / kDieselEnergy_jpl);
    if (t && std::abs(*t) > 0) std::fprintf(stderr, "  (%+.1f %%)", 100.0 * (f.energy(use(i)) - *t) / std::abs(*t));
    std::fprintf(stderr, "\n");
  }
  if (!truth) return;
  double se = 0;
  std::size_t n = 0, covered = 0;
  for (const CellResult& c : cells) {
    const double* t = true_crr(truth, c.id);
    if (t == nullptr || c.samples == 0) continue;
    se += (c.crr - *t) * (c.crr - *t);
    covered += *t >= c.crr_lo && *t <= c.crr_hi ? 1 : 0;
    ++n;
  }
  if (n > 0) {
    std::fprintf(stderr, "analyze: against the truth: RMSE %.5f over %zu cells, 90 %% intervals cover %zu (%.0f %%)\n",
                 std::sqrt(se / static_cast<double>(n)), n, covered, 100.0 * static_cast<double>(covered) / static_cast<double>(n));
  }
}

}  // namespace roadload::cli
