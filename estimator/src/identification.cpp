#include "roadload/identification.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace roadload {
namespace {

std::string format(const char* fmt, double a, double b, double c = 0) {
  char text[200];
  std::snprintf(text, sizeof text, fmt, a, b, c);
  return text;
}

}  // namespace

std::vector<std::string> drive_failures(const TripResult& trip, const IdentificationLimits& limits) {
  std::vector<std::string> out;
  const auto updates = static_cast<double>(trip.filter.updates + trip.filter.outliers);
  if (trip.filter.updates == 0) out.emplace_back("no speed update entered the filter");
  if (updates > 0) {
    const double share = static_cast<double>(trip.filter.outliers) / updates;
    if (share > limits.max_outlier_share) {
      out.push_back(
          format("the model does not predict this drive's speed: %.1f %% of the speed updates were outliers (at most %.1f %%)",
                 100.0 * share, 100.0 * limits.max_outlier_share));
    }
  }
  const double band = limits.nis_z * trip.mean_nis_se;
  if (trip.filter.updates > 0 && !(trip.mean_nis_se > 0)) {
    out.push_back(format("the filter's consistency cannot be judged: %.0f speed updates, mean NIS %.2f", updates, trip.mean_nis));
  } else if (trip.filter.updates > 0 && std::abs(trip.mean_nis - 1.0) > band) {
    // Either side withholds the number; the reader is told which failure it is (the fleet's
    // network model takes a cautious filter's estimate as evidence, not a missed model's).
    const bool below = trip.mean_nis < 1.0;
    std::string why(kNisInconsistent);
    why += format("%.2f outside 1 +- %.2f", trip.mean_nis, band);
    why += below ? kNisBelowBand : kNisAboveBand;
    why += below ? ": the speed strayed less than the filter allowed, so its interval is wider than the data warrant)"
                 : ": the speed strayed more than the model allows, so its estimate may be wrong)";
    out.push_back(std::move(why));
  }
  if (trip.fuel.time_s > 0) {
    const double share = trip.fuel.wheel_j > 0 ? std::abs(trip.fuel.unexplained_j()) / trip.fuel.wheel_j : INFINITY;
    if (!(share <= limits.max_unexplained_work)) {
      out.push_back(
          trip.fuel.wheel_j > 0
              ? format("the force balance does not close: it leaves %.1f %% of the work at the wheels unexplained (at most %.0f %%)",
                       100.0 * share, 100.0 * limits.max_unexplained_work)
              : format("the force balance cannot be closed: no work at the wheels is known (%.0f of %.0f ticks usable)",
                       static_cast<double>(trip.usable_ticks), static_cast<double>(trip.ticks)));
    }
  }
  // A wind of 3 m/s along the road moves the drag at 30 mph by half: taken as calm, it lands on CRR.
  if (trip.wind_samples == 0) {
    out.emplace_back(
        "no wind was measured (no weather station in the recording): the air's speed against the truck, and so "
        "its drag, is unknown");
  }
  const std::size_t fixes = trip.gnss_used + trip.gnss_off_route;
  if (trip.gnss_used < limits.min_fixes_on_route) {
    out.push_back(format("the drive is not placed on the route: %.0f GNSS fixes on it (at least %.0f)",
                         static_cast<double>(trip.gnss_used), static_cast<double>(limits.min_fixes_on_route)));
  } else if (static_cast<double>(trip.gnss_off_route) > limits.max_off_route_share * static_cast<double>(fixes)) {
    out.push_back(format("the GNSS track leaves the route: %.0f of %.0f fixes off it", static_cast<double>(trip.gnss_off_route),
                         static_cast<double>(fixes)));
  }
  return out;
}

std::vector<std::string> estimate_failures(double crr, double sigma, double max_sigma, const IdentificationLimits& limits) {
  std::vector<std::string> out;
  if (!std::isfinite(crr) || !std::isfinite(sigma)) {
    out.emplace_back("the estimate is not a number");
    return out;
  }
  if (sigma > max_sigma) out.push_back(format("its uncertainty %.5f exceeds the limit %.5f", sigma, max_sigma));
  if (crr < limits.min_crr || crr > limits.max_crr) {
    out.push_back(format("CRR %.5f lies outside what truck tires show (%.3f-%.3f)", crr, limits.min_crr, limits.max_crr));
  }
  return out;
}

void judge_cell(CellResult& cell, double max_sigma, const IdentificationLimits& limits, const std::vector<std::string>& drive) {
  std::vector<std::string> failures = estimate_failures(cell.crr, cell.crr_sigma, max_sigma, limits);
  failures.insert(failures.end(), drive.begin(), drive.end());
  cell.identified = failures.empty();
  cell.reason = cell.identified ? std::string() : "CRR not identified: " + join_reasons(failures);
}

std::vector<std::string> trip_failures(const TripResult& trip, bool usable, double max_sigma, const IdentificationLimits& limits) {
  std::vector<std::string> failures;
  if (!usable) failures.emplace_back("no usable force balance");
  for (auto& f : estimate_failures(trip.crr, trip.crr_sigma, max_sigma, limits)) failures.push_back(std::move(f));
  for (auto& f : drive_failures(trip, limits)) failures.push_back(std::move(f));
  return failures;
}

std::string join_reasons(const std::vector<std::string>& reasons) {
  std::string s;
  for (const std::string& r : reasons) s += (s.empty() ? "" : "; ") + r;
  return s;
}

void withhold(CellResult& c, const std::string& why) {
  c.identified = false;
  c.reason = c.reason.empty() ? "CRR not identified: " + why : c.reason + "; " + why;
}

void withhold(TripResult& trip, std::vector<CellResult>& cells, const std::string& why) {
  trip.identified = false;
  trip.not_identified.insert(trip.not_identified.begin(), why);
  for (CellResult& c : cells) withhold(c, why);
}

}  // namespace roadload
