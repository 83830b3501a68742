#include "roadload/network/mixed_model.hpp"

#include <cmath>
#include <limits>

#include "roadload/network/minimize.hpp"
#include "roadload/numbers.hpp"

namespace roadload::network {
namespace {

// The model's cross products, which do not change with the variances: K'WK and K'Wy for
// K = [X Z], and y'Wy.
struct Moments {
  Eigen::MatrixXd ktwk;
  Eigen::VectorXd ktwy;
  double ytwy = 0, log_weights = 0;
  std::size_t n = 0, p = 0;
  std::vector<std::size_t> term_of;  // each random effect's term
  std::vector<RandomTerm> terms;
};

Moments moments(const MixedModel& m) {
  Moments s;
  s.p = m.fixed_columns;
  s.terms = m.terms;
  std::size_t q = 0;
  for (std::size_t t = 0; t < m.terms.size(); ++t) {
    s.term_of.insert(s.term_of.end(), m.terms[t].levels, t);
    q += m.terms[t].levels;
  }
  s.ktwk = Eigen::MatrixXd::Zero(s.p + q, s.p + q);
  s.ktwy = Eigen::VectorXd::Zero(s.p + q);
  SparseEntries row;
  for (const MixedModel::Observation& o : m.observations) {
    row = o.fixed;
    for (const auto& [k, v] : o.random) row.emplace_back(s.p + k, v);
    for (const auto& [a, va] : row) {
      s.ktwy(a) += o.weight * va * o.y;
      for (const auto& [b, vb] : row) s.ktwk(a, b) += o.weight * va * vb;
    }
    s.ytwy += o.weight * o.y * o.y;
    s.log_weights += std::log(o.weight);
    ++s.n;
  }
  return s;
}

// The mixed-model equations' matrix for log-variances `phi` (residual first, then each term).
Eigen::MatrixXd equations(const Moments& s, const std::vector<double>& phi) {
  Eigen::MatrixXd c = s.ktwk / std::exp(phi[0]);
  for (std::size_t k = 0; k < s.term_of.size(); ++k) c(s.p + k, s.p + k) += std::exp(-phi[1 + s.term_of[k]]);
  return c;
}

// -2 log restricted likelihood, up to a constant (log|R| + log|G| + log|C| + y'Py).
double minus2_reml(const Moments& s, const std::vector<double>& phi) {
  const Eigen::LLT<Eigen::MatrixXd> llt(equations(s, phi));
  if (llt.info() != Eigen::Success) return HUGE_VAL;
  const Eigen::VectorXd theta = llt.solve(s.ktwy / std::exp(phi[0]));
  const double ypy = (s.ytwy - theta.dot(s.ktwy)) / std::exp(phi[0]);
  double log_g = 0;
  for (std::size_t t : s.term_of) log_g += phi[1 + t];
  const double log_c = 2 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  double prior = 0;
  for (std::size_t t = 0; t < s.terms.size(); ++t) {
    const RandomTerm& term = s.terms[t];
    if (term.prior_sd > 0 && term.prior_log_sd > 0)
      prior += std::pow((phi[1 + t] / 2 - std::log(term.prior_sd)) / term.prior_log_sd, 2);
  }
  return static_cast<double>(s.n) * phi[0] - s.log_weights + log_g + log_c + ypy + prior;
}

// The curvature of -2 log L at its minimum, by central differences in the log-variances.
Eigen::MatrixXd curvature(const Moments& s, const std::vector<double>& phi) {
  const std::size_t k = phi.size();
  constexpr double h = 0.05;
  Eigen::MatrixXd hess(k, k);
  const auto f = [&](std::size_t i, double di, std::size_t j, double dj) {
    std::vector<double> x = phi;
    x[i] += di;
    x[j] += dj;
    return minus2_reml(s, x);
  };
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = 0; j < k; ++j) {
      hess(i, j) = (f(i, h, j, h) - f(i, h, j, -h) - f(i, -h, j, h) + f(i, -h, j, -h)) / (4 * h * h);
    }
  }
  return hess;
}

}  // namespace

std::size_t MixedModel::random_index(std::size_t term, std::size_t level) const {
  std::size_t offset = 0;
  for (std::size_t t = 0; t < term; ++t) offset += terms[t].levels;
  return offset + level;
}

MixedModelFit fit_reml(const MixedModel& model) {
  const Moments s = moments(model);
  MixedModelFit fit;
  fit.fixed = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(s.p), kNaN);
  if (s.n <= s.p) return fit;
  // Start every variance at the data's own per-observation variance about zero, a scale the
  // simplex then moves by factors of e.
  const double start = std::log(std::max(s.ytwy / static_cast<double>(s.n) * 1e-2, 1e-300));
  const auto objective = [&](const std::vector<double>& phi) {
    for (double v : phi) {
      if (v < start - 30 || v > start + 30) return HUGE_VAL;
    }
    return minus2_reml(s, phi);
  };
  const Minimum best = minimize(objective, std::vector<double>(1 + model.terms.size(), start), 2.0);
  fit.minus2_reml = best.value;
  fit.evaluations = best.evaluations;
  fit.converged = best.converged && std::isfinite(best.value);
  if (!std::isfinite(best.value)) return fit;
  const Eigen::MatrixXd c = equations(s, best.x);
  const Eigen::LLT<Eigen::MatrixXd> llt(c);
  const Eigen::VectorXd theta = llt.solve(s.ktwy / std::exp(best.x[0]));
  const Eigen::MatrixXd cov = llt.solve(Eigen::MatrixXd::Identity(c.rows(), c.cols()));
  const auto p = static_cast<Eigen::Index>(s.p);
  fit.fixed = theta.head(p);
  fit.fixed_cov = cov.topLeftCorner(p, p);
  fit.random = theta.tail(theta.size() - p);
  fit.random_sd = cov.diagonal().tail(theta.size() - p).cwiseMax(0).cwiseSqrt();
  // sd = exp(phi / 2); its 90 % interval from the curvature where it is positive, else the
  // surface is flat there (a variance at its bound) and the interval runs to zero.
  const Eigen::MatrixXd hess = curvature(s, best.x);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(hess);
  const Eigen::MatrixXd phi_cov = lu.isInvertible()
                                      ? Eigen::MatrixXd(2 * lu.solve(Eigen::MatrixXd::Identity(hess.rows(), hess.cols())))
                                      : Eigen::MatrixXd();
  for (std::size_t k = 0; k < best.x.size(); ++k) {
    VarianceComponent v{k == 0 ? "residual" : model.terms[k - 1].name, std::exp(best.x[k] / 2), 0, kNaN};
    const double var_phi = phi_cov.size() ? phi_cov(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)) : kNaN;
    if (std::isfinite(var_phi) && var_phi > 0) {
      v.sd_lo = std::exp((best.x[k] - kZ90 * std::sqrt(var_phi)) / 2);
      v.sd_hi = std::exp((best.x[k] + kZ90 * std::sqrt(var_phi)) / 2);
    }
    (k == 0 ? fit.residual : fit.terms.emplace_back()) = v;
  }
  return fit;
}

}  // namespace roadload::network
