// Soft stiffness of an active element (Aulisa & Capodaglio eq. (26)):
//   r_I += mu C_E int_E [grad~ u~ + (grad~ u~)^T] grad~ N_I dV
// on the Gauss points of the element in the reference configuration x~ (A20: on u~ with respect to
// x~, as the paper says). mu is the shear modulus of the element's MPM body, C_E the element's
// soft-stiffness factor (element_flags.hpp). Linear in u~.
#pragma once

#include <vector>

#include "matpoint/core/dual.hpp"
#include "matpoint/implicit/element_geometry.hpp"
#include "matpoint/mesh/element_types.hpp"

namespace matpoint::implicit {

/// The Gauss points of one element in x~: gradients dN/dx~ and weights w_g det J_g.
template <class E>
struct GaussGeometry {
  std::vector<GradientMatrix<E>> G;
  std::vector<Eigen::Matrix<double, E::kNodes, 1>> N;
  std::vector<double> weight;
};

template <class E>
GaussGeometry<E> gauss_geometry(const NodeMatrix<E>& x, int points_per_direction,
                                mesh::ElementVariant variant) {
  const auto& rule = mesh::gauss_rule<E>(points_per_direction);
  GaussGeometry<E> g;
  for (std::size_t k = 0; k < rule.points.size(); ++k) {
    double det = 0.0;
    g.G.push_back(physical_gradients<E>(x, rule.points[k], variant, &det));
    g.N.push_back(E::values(rule.points[k], variant));
    g.weight.push_back(rule.weights[k] * det);
  }
  return g;
}

/// Adds mu C_E int (grad u + grad u^T) grad N_I to r (u, r node-major, D per node).
template <class E, class S>
void add_soft_stiffness_residual(const GaussGeometry<E>& g, double mu_times_ce, const S* u, S* r) {
  constexpr int n = E::kNodes, D = E::kDim;
  for (std::size_t k = 0; k < g.weight.size(); ++k) {
    const auto& G = g.G[k];
    Eigen::Matrix<S, D, D> grad = Eigen::Matrix<S, D, D>::Zero();
    for (int I = 0; I < n; ++I)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) add_product(grad(i, j), u[I * D + i], G(I, j));
    const Eigen::Matrix<S, D, D> sym = (mu_times_ce * g.weight[k]) * (grad + grad.transpose());
    for (int I = 0; I < n; ++I)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) add_product(r[I * D + i], sym(i, j), G(I, j));
  }
}

}  // namespace matpoint::implicit
