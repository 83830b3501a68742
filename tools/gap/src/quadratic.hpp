#pragma once
// The chi-square of a diagnosis as a quadratic in its effects' magnitudes, the truck's nominal
// offsets profiled out: what every fit of diagnosis.cpp minimises and judges.
#include <Eigen/Cholesky>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "roadload/gap/diagnosis.hpp"

namespace roadload::gap::detail {

inline constexpr std::uint8_t kBothHalves = 255;

inline bool in_half(const FeatureKey& k, std::uint8_t half) { return half == kBothHalves || k.half == half; }

// The chi-square of z minus a candidate set's response and the nominal parameters' as a function
// of the magnitudes' offsets u from base and the nominal offsets t (in prior sigmas), over one
// half: zz - 2 c'h + c'Gc with c = (u1, u1^2, u2, u2^2, ..., t). For given u the best t is linear
// (with its unit prior), so a fit searches over u alone.
struct Quadratic {
  Eigen::MatrixXd g;
  Eigen::VectorXd h;
  double zz = 0;
  std::size_t n = 0;
  Eigen::Index ne = 0, nn = 0;                // effect and nominal columns
  Eigen::LDLT<Eigen::MatrixXd> nominal_info;  // G_nn + I: the nominal block with its prior

  // Beside effects, each nominal offset is held within `truck_sigmas` or the offset the truck
  // takes fitted alone, whichever is farther (bound; empty when unbounded).
  Eigen::VectorXd bound;

  Quadratic(const Problem& p, const std::vector<std::size_t>& set, std::uint8_t half,
            double truck_sigmas = std::numeric_limits<double>::infinity()) {
    ne = static_cast<Eigen::Index>(2 * set.size());
    nn = static_cast<Eigen::Index>(p.nominal.size());
    Eigen::MatrixXd basis(p.z.size(), ne + nn);
    for (std::size_t i = 0; i < set.size(); ++i) {
      basis.col(static_cast<Eigen::Index>(2 * i)) = p.candidates[set[i]].a;
      basis.col(static_cast<Eigen::Index>(2 * i + 1)) = p.candidates[set[i]].b;
    }
    for (Eigen::Index j = 0; j < nn; ++j) basis.col(ne + j) = p.nominal[static_cast<std::size_t>(j)].per_sigma;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index r = 0; r < p.z.size(); ++r) {
      if (std::isfinite(p.z(r)) && in_half(p.keys[static_cast<std::size_t>(r)], half)) rows.push_back(r);
    }
    Eigen::MatrixXd b(static_cast<Eigen::Index>(rows.size()), ne + nn);
    Eigen::VectorXd z(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      b.row(static_cast<Eigen::Index>(i)) = basis.row(rows[i]);
      z(static_cast<Eigen::Index>(i)) = p.z(rows[i]);
    }
    g = b.transpose() * b;
    h = b.transpose() * z;
    zz = z.squaredNorm();
    n = rows.size();
    nominal_info.compute(g.bottomRightCorner(nn, nn) + Eigen::MatrixXd::Identity(nn, nn));
    if (ne > 0 && nn > 0 && std::isfinite(truck_sigmas))
      bound = free_theta(Eigen::VectorXd::Zero(ne)).cwiseAbs().cwiseMax(truck_sigmas);
  }
  Eigen::VectorXd effect_coeffs(const std::vector<double>& u) const {
    Eigen::VectorXd c(ne);
    for (std::size_t i = 0; i < u.size(); ++i) {
      c(static_cast<Eigen::Index>(2 * i)) = u[i];
      c(static_cast<Eigen::Index>(2 * i + 1)) = u[i] * u[i];
    }
    return c;
  }
  Eigen::VectorXd free_theta(const Eigen::VectorXd& ce) const {
    return nominal_info.solve(h.tail(nn) - g.bottomLeftCorner(nn, ne) * ce);
  }
  // The nominal offsets that fit best beside the effect coefficients ce, within the bound: an
  // offset beyond it is held there (the farthest first) and the others refitted beside it.
  Eigen::VectorXd theta(const Eigen::VectorXd& ce) const {
    if (nn == 0) return {};
    Eigen::VectorXd t = free_theta(ce);
    if (bound.size() == 0) return t;
    std::vector<bool> held(static_cast<std::size_t>(nn), false);
    for (Eigen::Index pass = 0; pass < nn; ++pass) {
      Eigen::Index worst = -1;
      double excess = 0;
      for (Eigen::Index j = 0; j < nn; ++j) {
        if (!held[static_cast<std::size_t>(j)] && std::abs(t(j)) - bound(j) > excess) worst = j, excess = std::abs(t(j)) - bound(j);
      }
      if (worst < 0) break;
      held[static_cast<std::size_t>(worst)] = true;
      t(worst) = std::copysign(bound(worst), t(worst));
      refit_free(ce, held, t);
    }
    return t;
  }
  // The offsets not held, refitted (with their prior) beside the held ones and the effects.
  void refit_free(const Eigen::VectorXd& ce, const std::vector<bool>& held, Eigen::VectorXd& t) const {
    std::vector<Eigen::Index> free;
    for (Eigen::Index j = 0; j < nn; ++j) {
      if (!held[static_cast<std::size_t>(j)]) free.push_back(j);
    }
    if (free.empty()) return;
    const auto nf = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd a(nf, nf);
    Eigen::VectorXd rhs(nf);
    for (Eigen::Index r = 0; r < nf; ++r) {
      const Eigen::Index i = ne + free[static_cast<std::size_t>(r)];
      rhs(r) = h(i) - g.row(i).head(ne).dot(ce);
      for (Eigen::Index j = 0; j < nn; ++j) {
        if (held[static_cast<std::size_t>(j)]) rhs(r) -= g(i, ne + j) * t(j);
      }
      for (Eigen::Index c = 0; c < nf; ++c) a(r, c) = g(i, ne + free[static_cast<std::size_t>(c)]) + (r == c ? 1.0 : 0.0);
    }
    const Eigen::VectorXd tf = a.ldlt().solve(rhs);
    for (Eigen::Index r = 0; r < nf; ++r) t(free[static_cast<std::size_t>(r)]) = tf(r);
  }
  double misfit(const Eigen::VectorXd& ce, const Eigen::VectorXd& t) const {
    Eigen::VectorXd c(ne + nn);
    c << ce, t;
    return zz - 2.0 * c.dot(h) + c.dot(g * c);
  }
  // What a fit minimises: the misfit with the best nominal offsets, plus their prior.
  double sse(const std::vector<double>& u) const {
    const Eigen::VectorXd ce = effect_coeffs(u);
    const Eigen::VectorXd t = theta(ce);
    return misfit(ce, t) + t.squaredNorm();
  }
  // This half's misfit at u with the nominal offsets another half's fit chose for u.
  double judged(const Quadratic& fit, const std::vector<double>& u) const {
    const Eigen::VectorXd ce = effect_coeffs(u);
    return misfit(ce, fit.theta(ce));
  }
};

}  // namespace roadload::gap::detail
