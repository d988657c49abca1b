// Local maximum-entropy (LME) shape functions (Arroyo & Ortiz 2006; Iaconeta et al. 2017 §4.2.2,
// eqs. (59)-(61); extraction §6.3, A15), values and gradients at one point x from its cloud.
// With one beta = gamma / h^2 per point the Pareto problem (61) has the solution
//
//   p_a(x) = exp(-beta |x - x_a|^2 + lambda* . (x - x_a)) / Z(x, lambda*),
//   lambda* = argmin ln Z(x, lambda),  Z = sum_b exp(-beta |x - x_b|^2 + lambda . (x - x_b)),
//
// found by Newton on the convex dual: r = sum p_a (x - x_a) (= grad ln Z),
// J = sum p_a (x - x_a)(x - x_a)^T - r r^T (= its Hessian), lambda <- lambda - J^-1 r, with an
// Armijo backtracking line search on ln Z. The gradient is closed form (Arroyo & Ortiz 2006):
//
//   grad p_a = -p_a J^-1 (x - x_a).
//
// Newton runs in the dimensionless offsets d_a = sqrt(beta) (x - x_a) and mu = lambda / sqrt(beta),
// so its tolerance and the condition number do not depend on the units. The safeguard of the
// authors' code (extraction §6.3, §6.5): the point is flagged IllConditioned when the inverse
// condition number 1 / (|J|_F |J^-1|_F) falls below a tolerance (1e-9).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <span>

#include "matpoint/core/types.hpp"
#include "matpoint/shape/meshfree_status.hpp"

namespace matpoint {

struct LmeParameters {
  double beta = 1.0;  // gamma / h^2 (eq. (61))
  double tolerance =
      1e-13;  // on |r| sqrt(beta), the residual of linear reproduction in units of 1/sqrt(beta)
  int max_iterations = 100;             // Newton steps on lambda
  double min_inverse_condition = 1e-9;  // 1 / (|J|_F |J^-1|_F) below this: IllConditioned (extraction §6.3)
  double armijo = 1e-4;                 // sufficient decrease of ln Z per unit of r . step
};

template <int D>
struct LmeOutcome {
  MeshfreeStatus status = MeshfreeStatus::Empty;
  int iterations = 0;
  double inverse_condition = 0.0;  // of the final Hessian J
  Vec<D> lambda = Vec<D>::Zero();  // lambda* (physical units, 1/length)
};

namespace lme_detail {

/// p_a (into N), ln Z, r and J at mu for the scaled offsets d_a.
template <int D>
struct DualState {
  double log_z = 0.0;
  Vec<D> r = Vec<D>::Zero();
  Mat<D> J = Mat<D>::Zero();
};

template <int D>
DualState<D> evaluate(std::span<const Vec<D>> d, const Vec<D>& mu, std::span<double> p) {
  double f_max = -INFINITY;
  for (std::size_t a = 0; a < d.size(); ++a) {
    p[a] = -d[a].squaredNorm() + mu.dot(d[a]);
    f_max = std::max(f_max, p[a]);
  }
  double z = 0.0;
  for (std::size_t a = 0; a < d.size(); ++a) z += (p[a] = std::exp(p[a] - f_max));
  DualState<D> s;
  s.log_z = f_max + std::log(z);
  for (std::size_t a = 0; a < d.size(); ++a) {
    p[a] /= z;
    s.r.noalias() += p[a] * d[a];
    s.J.noalias() += p[a] * d[a] * d[a].transpose();
  }
  s.J.noalias() -= s.r * s.r.transpose();
  return s;
}

}  // namespace lme_detail

/// LME shape functions N[i] and gradients dN[i] for the cloud nodes[i]; scratch must hold
/// nodes.size() vectors. lambda0 is the starting multiplier (zero, or the last step's lambda*).
template <int D>
LmeOutcome<D> lme_shape_functions(const Vec<D>& x, std::span<const Vec<D>> nodes, const LmeParameters& par,
                                  std::span<double> N, std::span<Vec<D>> dN,
                                  const Vec<D>& lambda0 = Vec<D>::Zero()) {
  LmeOutcome<D> out;
  if (nodes.empty()) return out;
  const double sb = std::sqrt(par.beta);
  std::span<Vec<D>> d = dN;  // the scaled offsets live in dN until the gradients overwrite them
  for (std::size_t a = 0; a < nodes.size(); ++a) d[a] = sb * (x - nodes[a]);
  const std::span<const Vec<D>> dc(d.data(), d.size());
  Vec<D> mu = lambda0 / sb;
  auto s = lme_detail::evaluate<D>(dc, mu, N);
  out.status = MeshfreeStatus::NotConverged;
  for (; out.iterations <= par.max_iterations; ++out.iterations) {
    if (s.r.norm() <= par.tolerance) {
      out.status = MeshfreeStatus::Ok;
      break;
    }
    if (out.iterations == par.max_iterations) break;
    const Eigen::LDLT<Mat<D>> ldlt(s.J);
    Vec<D> step = -ldlt.solve(s.r);
    double slope = s.r.dot(step);
    if (!(ldlt.info() == Eigen::Success && slope < 0.0 && step.allFinite())) {
      step = -s.r;  // J singular to working precision: steepest descent keeps ln Z decreasing
      slope = -s.r.squaredNorm();
    }
    // Armijo on ln Z; close to the solution (|r| < 1e-6, quadratic convergence) the decrease of
    // ln Z (~|r|^2) drops below its round-off, so there a step that reduces |r| is accepted.
    double t = 1.0;
    auto trial = lme_detail::evaluate<D>(dc, mu + step, N);
    const double r_norm = s.r.norm();
    auto accepted = [&] {
      return trial.log_z <= s.log_z + par.armijo * t * slope || (r_norm < 1e-6 && trial.r.norm() < r_norm);
    };
    while (!accepted() && t > 1e-12) {
      t *= 0.5;
      trial = lme_detail::evaluate<D>(dc, mu + t * step, N);
    }
    if (!(t > 1e-12)) break;  // no decrease possible: x is (numerically) outside the hull
    mu += t * step;
    s = trial;
  }
  out.lambda = mu * sb;
  const Mat<D> Jinv = s.J.inverse();
  out.inverse_condition = 1.0 / (s.J.norm() * Jinv.norm());
  if (!std::isfinite(out.inverse_condition)) out.inverse_condition = 0.0;
  if (out.status == MeshfreeStatus::Ok && !(out.inverse_condition >= par.min_inverse_condition))
    out.status = MeshfreeStatus::IllConditioned;
  // grad p_a = -p_a J^-1 (x - x_a) in physical units: J = J_scaled / beta, x - x_a = d_a / sqrt(beta).
  for (std::size_t a = 0; a < nodes.size(); ++a) dN[a] = (-N[a] * sb) * (Jinv * d[a]);
  return out;
}

}  // namespace matpoint
