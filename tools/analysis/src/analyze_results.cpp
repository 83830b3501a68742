#include "analyze_results.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string_view>

#include "roadload/recording/csv.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/tire_crr.hpp"

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

}  // namespace

void print_cells(const std::vector<CellResult>& cells, const Truth* truth) {
  std::printf("%-6s %9s %9s %9s %7s %9s%s\n", "cell", "crr", "crr_lo", "crr_hi", "samples", "roll_l",
              truth ? "     truth  inside" : "");
  for (const CellResult& c : cells) {
    if (c.samples == 0) {
      std::printf("%-6s %9s %9s %9s %7zu %9s  %s\n", c.id.c_str(), "-", "-", "-", c.samples, "-", c.reason.c_str());
      continue;
    }
    std::printf("%-6s %9.5f %9.5f %9.5f %7zu %9.5f", c.id.c_str(), c.crr, c.crr_lo, c.crr_hi, c.samples,
                c.fuel.liters(FuelUse::rolling));
    if (const double* t = true_crr(truth, c.id)) std::printf("   %7.5f  %s", *t, *t >= c.crr_lo && *t <= c.crr_hi ? "yes" : "no");
    std::printf("\n");
  }
}

namespace {

// RMSE and interval coverage of the cells' CRR against the true CRR.
void print_against_truth(const char* what, const std::vector<CellResult>& cells, const Truth& truth) {
  double se = 0;
  std::size_t n = 0, covered = 0;
  for (const CellResult& c : cells) {
    const double* t = true_crr(&truth, c.id);
    if (c.samples == 0 || t == nullptr) continue;
    se += (c.crr - *t) * (c.crr - *t);
    covered += *t >= c.crr_lo && *t <= c.crr_hi ? 1 : 0;
    ++n;
  }
  if (n == 0) return;
  std::fprintf(stderr, "analyze: %s against the truth: RMSE %.5f over %zu cells, 90 %% intervals cover %zu (%.0f %%)\n", what,
               std::sqrt(se / static_cast<double>(n)), n, covered, 100.0 * static_cast<double>(covered) / static_cast<double>(n));
}

}  // namespace

void print_pavements(const std::vector<PavementResult>& pavements) {
  for (const PavementResult& p : pavements) {
    const CellResult& c = p.crr;
    if (c.samples == 0) {
      std::fprintf(stderr, "analyze: pavement %-16s %s\n", c.id.c_str(), c.reason.c_str());
      continue;
    }
    std::fprintf(stderr, "analyze: pavement %-16s CRR %.5f [%.5f, %.5f] %s, rolling %.2f L/100 km over %.0f m\n", c.id.c_str(), c.crr,
                 c.crr_lo, c.crr_hi, c.identified ? "identified" : "NOT identified", p.rolling_l_per_100km(), p.distance_m);
  }
}

void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth,
                const VibrationAnalysis* vibration) {
  std::fprintf(stderr,
               "analyze: trip CRR %.5f +- %.5f (%s), CdA %.2f m^2, mass %.0f +- %.0f kg, %zu of %zu ticks usable (%zu coasting), "
               "mean NIS %.2f +- %.2f\n",
               trip.crr, trip.crr_sigma, trip.identified ? "identified" : "NOT identified", trip.cda_m2, trip.mass_kg,
               trip.mass_sigma_kg, trip.usable_ticks, trip.ticks, trip.coasting_ticks, trip.mean_nis, 1.96 * trip.mean_nis_se);
  for (const std::string& why : trip.not_identified) std::fprintf(stderr, "analyze: not identified: %s\n", why.c_str());
  const FuelBreakdown& f = trip.fuel;
  std::fprintf(stderr,
               "analyze: fuel %.3f L measured (LFE1), %.3f L of it while the engine's torques were unknown; "
               "rows sum to %.3f L (closure %+.2f %%)\n",
               f.fuel_l, f.unsplit_l, f.sum_l(), 100.0 * f.closure());
  for (std::size_t i = 0; i < kUses; ++i) {
    std::fprintf(stderr, "  %-13s %8.4f L %6.1f %%", to_string(use(i)), f.liters(use(i)),
                 f.fuel_l > 0 ? 100.0 * f.liters(use(i)) / f.fuel_l : 0.0);
    const auto t = truth ? truth_energy_j(*truth, use(i)) : std::nullopt;
    if (t) std::fprintf(stderr, "   truth %8.4f L", *t / kDieselEnergy_jpl);
    if (t && std::abs(*t) > 0) std::fprintf(stderr, "  (%+.1f %%)", 100.0 * (f.energy(use(i)) - *t) / std::abs(*t));
    std::fprintf(stderr, "\n");
  }
  if (!truth) return;
  print_against_truth("CRR", cells, *truth);
  if (vibration == nullptr) return;
  // Cells the accelerometers did not measure keep the force balance's CRR: only the measured count.
  std::vector<CellResult> tires = with_tire_crr(cells, *vibration);
  for (std::size_t i = 0; i < tires.size(); ++i) {
    if (vibration->cell_power(i).segments == 0) tires[i].samples = 0;
  }
  print_against_truth("tires' CRR (less the dampers' and tires' dissipation)", tires, *truth);
}

}  // namespace roadload::cli
