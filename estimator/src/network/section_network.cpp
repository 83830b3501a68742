#include "roadload/network/section_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "roadload/numbers.hpp"

namespace roadload::network {
namespace {

// RMS of (v / v_ref)^2 - 1 below which speeds are one speed: 0.1 is 30 against 33 mph.
constexpr double kMinSpeedSpread = 0.1;

enum Term : std::size_t { kTruck, kTruckDrag };

double reference_speed(const std::vector<SectionObservation>& obs) {
  double sum = 0;
  for (const SectionObservation& o : obs) sum += o.speed_mps * o.speed_mps;
  return std::sqrt(sum / static_cast<double>(obs.size()));
}

// Relative weights from the cells' own sigmas, about their median so the residual's spread
// stays in CRR units for a typical cell.
std::vector<double> weights(const std::vector<SectionObservation>& obs) {
  std::vector<double> sigmas;
  for (const SectionObservation& o : obs) sigmas.push_back(o.crr_sigma);
  std::nth_element(sigmas.begin(), sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2), sigmas.end());
  const double median = sigmas[sigmas.size() / 2];
  std::vector<double> w;
  for (const SectionObservation& o : obs) w.push_back(o.crr_sigma > 0 ? std::pow(median / o.crr_sigma, 2) : 1.0);
  return w;
}

}  // namespace

SectionNetworkFit fit_section_network(const std::vector<SectionObservation>& obs, std::size_t sections, std::size_t drives,
                                      std::size_t trucks, const SectionNetworkPriors& priors) {
  SectionNetworkFit out;
  out.sections.assign(sections, {kNaN, kNaN, kNaN, kNaN});
  out.trucks.assign(trucks, {kNaN, kNaN, kNaN});
  if (obs.empty()) return out;
  out.reference_speed_mps = reference_speed(obs);
  // Only sections driven are columns; a drag slope only where the speeds differ enough to tell
  // one (a fleet at one speed cannot separate drag from tires).
  std::vector<std::size_t> column(sections, sections);
  std::size_t driven = 0;
  for (const SectionObservation& o : obs) {
    if (column[o.section] == sections) column[o.section] = driven++;
  }
  double x_spread = 0;
  for (const SectionObservation& o : obs) x_spread += std::pow(std::pow(o.speed_mps / out.reference_speed_mps, 2) - 1, 2);
  const bool drag = std::sqrt(x_spread / static_cast<double>(obs.size())) > kMinSpeedSpread;
  if (obs.size() <= driven + (drag ? 1 : 0)) return out;
  MixedModel m;
  m.fixed_columns = driven + (drag ? 1 : 0);
  m.terms = {{"truck", trucks, priors.truck_sd, priors.log_sd}};
  if (drag) m.terms.push_back({"truck drag", trucks, priors.truck_drag_sd, priors.log_sd});
  const std::size_t drive_term = m.terms.size();
  m.terms.push_back({"drive", drives, 0, 0});
  const std::vector<double> w = weights(obs);
  for (std::size_t i = 0; i < obs.size(); ++i) {
    const SectionObservation& o = obs[i];
    const double x = std::pow(o.speed_mps / out.reference_speed_mps, 2) - 1;
    MixedModel::Observation row{o.crr, w[i], {{column[o.section], 1.0}}, {{m.random_index(kTruck, o.truck), 1.0}}};
    if (drag) {
      row.fixed.emplace_back(driven, x);
      row.random.emplace_back(m.random_index(kTruckDrag, o.truck), x + 1);
    }
    row.random.emplace_back(m.random_index(drive_term, o.drive), 1.0);
    m.observations.push_back(std::move(row));
  }
  const MixedModelFit fit = fit_reml(m);
  out.evaluations = fit.evaluations;
  // A fit whose simplex did not settle gives no section an estimate: numbers from it would look
  // like answers. network.json then says "fitted": false.
  out.fitted = fit.converged && std::isfinite(fit.fixed(0));
  if (!out.fitted) return out;
  for (std::size_t s = 0; s < sections; ++s) {
    if (column[s] == sections) continue;
    const auto k = static_cast<Eigen::Index>(column[s]);
    const double sd = std::sqrt(std::max(fit.fixed_cov(k, k), 0.0));
    out.sections[s] = {fit.fixed(k), sd, fit.fixed(k) - kZ90 * sd, fit.fixed(k) + kZ90 * sd};
  }
  if (drag) out.fleet_speed_slope = fit.fixed(static_cast<Eigen::Index>(driven));
  for (std::size_t t = 0; t < trucks; ++t) {
    const auto a = static_cast<Eigen::Index>(m.random_index(kTruck, t));
    const double slope = drag ? fit.random(static_cast<Eigen::Index>(m.random_index(kTruckDrag, t))) : 0.0;
    out.trucks[t] = {fit.random(a), fit.random_sd(a), slope};
  }
  out.cell = fit.residual;
  out.truck = fit.terms[kTruck];
  if (drag) out.truck_drag = fit.terms[kTruckDrag];
  out.drive = fit.terms[drive_term];
  return out;
}

}  // namespace roadload::network
