// Inverse isoparametric map of one element: the local coordinates xi with x(xi) = sum_i x_i N_i(xi)
// = x, by Newton's method xi <- xi - J(xi)^{-1} (x(xi) - x), J = dx/dxi (Aulisa & Capodaglio §3.3
// "inverse mapping", after Capodaglio & Aulisa 2017; extraction §7 "Point location"). Affine
// elements (T3, parallelogram Q4/Hex8, straight T6/Q9) converge in one step; curved Q9 in a few.
#pragma once

#include <algorithm>
#include <limits>
#include <optional>

#include "matpoint/mesh/element_types.hpp"

namespace matpoint::mesh {

/// Newton iterations allowed, and the step (in reference units) below which xi counts as converged.
inline constexpr int kInverseMapIterations = 25;
inline constexpr double kInverseMapStep = 1e-14;
/// Residual at the rounding level of the coordinates: |x(xi) - x| <= this * eps * max |coordinate|
/// also counts as converged (the step may then stay above kInverseMapStep for far-off origins).
inline constexpr double kInverseMapRounding = 16.0;

/// xi with x(xi) = x for the element with node coordinates `nodes` (one row per local node),
/// starting from `xi`; nullopt when Newton fails: a singular or inverted Jacobian, a step that
/// leaves |xi| <= 4 (the point is far outside this element), or no convergence.
template <class E>
std::optional<Vec<E::kDim>> inverse_map(const Eigen::Matrix<double, E::kNodes, E::kDim>& nodes,
                                        const Vec<E::kDim>& x, Vec<E::kDim> xi, ElementVariant variant = 0) {
  const double rounding = kInverseMapRounding * std::numeric_limits<double>::epsilon() *
                          std::max(nodes.cwiseAbs().maxCoeff(), x.cwiseAbs().maxCoeff());
  for (int it = 0; it < kInverseMapIterations; ++it) {
    const Vec<E::kDim> residual = nodes.transpose() * E::values(xi, variant) - x;
    const Mat<E::kDim> jac = nodes.transpose() * E::gradients(xi, variant);
    if (!(jac.determinant() > 0.0)) return std::nullopt;
    const Vec<E::kDim> step = jac.inverse() * residual;
    xi -= step;
    if (!(xi.template lpNorm<Eigen::Infinity>() <= 4.0)) return std::nullopt;
    if (step.template lpNorm<Eigen::Infinity>() <= kInverseMapStep ||
        residual.template lpNorm<Eigen::Infinity>() <= rounding)
      return xi;
  }
  return std::nullopt;
}

}  // namespace matpoint::mesh
