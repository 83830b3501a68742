#include "noise_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "roadload/numbers.hpp"

namespace roadload::gap {
namespace {

// Each feature's scatter over the residuals, pooled with its channel's so eight drives do not make
// a few features look too quiet, and never below the channel's resolution.
Eigen::VectorXd scatter(const ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals) {
  const auto n = lib.baseline.size();
  Eigen::VectorXd own = Eigen::VectorXd::Zero(n), count = Eigen::VectorXd::Zero(n);
  for (const Eigen::VectorXd& d : residuals) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::isfinite(d(i))) own(i) += d(i) * d(i), count(i) += 1;
    }
  }
  std::map<std::pair<std::string, std::string>, std::pair<double, double>> pooled;
  auto group = [&](Eigen::Index i) -> auto& {
    const FeatureKey& k = lib.keys[static_cast<std::size_t>(i)];
    return pooled[{k.run, k.channel}];
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    group(i).first += own(i);
    group(i).second += count(i);
  }
  constexpr double kPrior = 4.0;
  Eigen::VectorXd sigma(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& p = group(i);
    const double channel_var = p.second > 0 ? p.first / p.second : kNaN;
    const double var = (own(i) + kPrior * channel_var) / (count(i) + kPrior);
    const double floor = resolution(lib.keys[static_cast<std::size_t>(i)].channel);
    sigma(i) = count(i) >= 2 && std::isfinite(var) ? std::max(std::sqrt(var), floor) : kNaN;
  }
  return sigma;
}

// One noise drive's residual as a problem: whitened, with the nominal columns and no candidates.
Problem as_problem(const ModelLibrary& lib, const Eigen::VectorXd& d, const Eigen::VectorXd& sigma) {
  Problem p;
  p.keys = lib.keys;
  p.z = d.cwiseQuotient(sigma);
  p.nominal = nominal_columns(lib, sigma);
  return p;
}

// The drive's residual once its truck is fitted on half 0, as the diagnosis fits a real one.
Eigen::VectorXd calibrated(const ModelLibrary& lib, const Eigen::VectorXd& d, const Eigen::VectorXd& sigma) {
  const NominalFit f = fit_nominal(as_problem(lib, d, sigma), {}, {});
  Eigen::VectorXd out = d;
  for (std::size_t j = 0; j < f.shift_sigma.size(); ++j)
    out -= lib.nominal_delta.col(static_cast<Eigen::Index>(j)) * f.shift_sigma[j];
  return out;
}

}  // namespace

double resolution(const std::string& channel) {
  // CCVS1 speed 1/256 km/h, FD1 fan 0.125 rpm; below 1 N m of engine torque, 0.05 L/h, 2 cm of
  // height or 0.1 dB of vibration the model is as good as anyone needs.
  if (channel == "speed_mps" || channel == "speed_sd_mps") return 0.005;
  if (channel == "fan_rpm") return 2.0;
  if (channel == "torque_nm" || channel == "torque_sd_nm") return 1.0;
  if (channel == "fuel_lph") return 0.05;
  if (channel == "gnss_alt_m") return 0.02;
  return 0.1;  // psd_db
}

void set_nominal_delta(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& plus_sigma) {
  lib.nominal_delta.resize(lib.baseline.size(), static_cast<Eigen::Index>(plus_sigma.size()));
  for (std::size_t j = 0; j < plus_sigma.size(); ++j) {
    lib.nominal_delta.col(
        static_cast<Eigen::Index>(j)) = (plus_sigma[j] - lib.baseline).unaryExpr([](double v) { return std::isfinite(v) ? v : 0.0; });
  }
  // The nominal truck is fitted on the longitudinal channels alone. Its mass moves the body's
  // modes too, but the vibration model's own errors are larger than that: fitted on vibration,
  // the mass and the efficiency would take up what a vibration effect's response leaves, in
  // shifts that cancel in the torque.
  for (std::size_t i = 0; i < lib.keys.size(); ++i) {
    if (lib.keys[i].channel.starts_with("psd_db")) lib.nominal_delta.row(static_cast<Eigen::Index>(i)).setZero();
  }
}

std::vector<NominalColumn> nominal_columns(const ModelLibrary& lib, const Eigen::VectorXd& sigma) {
  std::vector<NominalColumn> out;
  if (lib.priors.empty()) return out;
  for (std::size_t j = 0; j < lib.priors.front().size(); ++j) {
    const NominalPrior& p = lib.priors.front()[j];
    NominalColumn c{std::string(nominal_name(p.id)), std::string(nominal_unit(p.id)), p.value, p.sigma, {}};
    c.per_sigma = lib.nominal_delta.col(static_cast<Eigen::Index>(j)).cwiseQuotient(sigma).unaryExpr([](double v) {
      return std::isfinite(v) ? v : 0.0;
    });
    out.push_back(std::move(c));
  }
  return out;
}

void set_noise_floor(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals,
                     const std::vector<std::vector<double>>& trucks) {
  // The drives' trucks differ from the model's: a floor of their raw scatter would hide every
  // effect behind the truck's spread. Fit each drive's truck against the floor so far, and take
  // the scatter of what is left; twice, as the floor itself sets the fit's weights.
  lib.sigma = scatter(lib, residuals);
  for (int pass = 0; pass < 2 && lib.nominal_delta.cols() > 0; ++pass) {
    std::vector<Eigen::VectorXd> left;
    for (const Eigen::VectorXd& d : residuals) left.push_back(calibrated(lib, d, lib.sigma));
    lib.sigma = scatter(lib, left);
  }
  // What a drive with nothing missing from the model scores on the held-out half, and how far its
  // truck's fit is from the truck it drove.
  std::vector<double> null_chi2;
  lib.nominal_miss.assign(static_cast<std::size_t>(lib.nominal_delta.cols()), 0.0);
  for (std::size_t k = 0; k < residuals.size(); ++k) {
    const NominalFit f = fit_nominal(as_problem(lib, residuals[k], lib.sigma), {}, {});
    null_chi2.push_back(f.chi2_half1_after);
    for (std::size_t j = 0; j < lib.nominal_miss.size() && j < f.shift_sigma.size(); ++j) {
      const double miss = f.shift_sigma[j] - trucks[k][j];
      lib.nominal_miss[j] += miss * miss / static_cast<double>(residuals.size());
    }
  }
  for (double& m : lib.nominal_miss) m = std::sqrt(m);
  lib.null_chi2_count = null_chi2.size();
  lib.null_chi2_mean = 0;
  for (double c : null_chi2) lib.null_chi2_mean += c / static_cast<double>(null_chi2.size());
  double ss = 0;
  for (double c : null_chi2) ss += (c - lib.null_chi2_mean) * (c - lib.null_chi2_mean);
  lib.null_chi2_sd = std::sqrt(ss / std::max<double>(1.0, static_cast<double>(null_chi2.size()) - 1.0));
}

void widen_by_miss(NominalFit& fit, const ModelLibrary& lib, const std::vector<NominalColumn>& columns) {
  // The 95th percentile of Student's t with as many degrees of freedom as noise drives (a
  // Cornish-Fisher expansion about the normal's 1.645; within 0.01 from 3 drives up).
  const double nu = std::max<double>(1.0, static_cast<double>(lib.null_chi2_count));
  const double z = 1.645, z3 = z * z * z, z5 = z3 * z * z;
  const double t = z + (z3 + z) / (4 * nu) + (5 * z5 + 16 * z3 + 3 * z) / (96 * nu * nu);
  for (std::size_t j = 0; j < fit.value.size() && j < lib.nominal_miss.size(); ++j) {
    const double curvature = fit.hi[j] - fit.value[j];
    const double miss = t * lib.nominal_miss[j] * columns[j].sigma;
    const double half = std::sqrt(curvature * curvature + miss * miss);
    fit.lo[j] = fit.value[j] - half;
    fit.hi[j] = fit.value[j] + half;
  }
}

}  // namespace roadload::gap
