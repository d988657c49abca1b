// Lumped-mass equations of the nodes that belong only to inactive elements (Aulisa & Capodaglio
// eq. (27)): r_I = u_I int_E^ N_I dV ~ u_I sum_g w_g N_I(x_g) det J_g on the undeformed element, for
// the nodes I of the inactive element E that are in I_ib. Summed over elements this is a row-sum
// lumped mass times u_I, so the solution is u_I = 0 and the system keeps its size (eq. (32)).
#pragma once

#include "matpoint/implicit/particle_newmark/soft_stiffness.hpp"

namespace matpoint::implicit {

/// int_E N_I dV per local node on the Gauss points of g.
template <class E>
Eigen::Matrix<double, E::kNodes, 1> lumped_node_masses(const GaussGeometry<E>& g) {
  Eigen::Matrix<double, E::kNodes, 1> m = Eigen::Matrix<double, E::kNodes, 1>::Zero();
  for (std::size_t k = 0; k < g.weight.size(); ++k) m += g.weight[k] * g.N[k];
  return m;
}

/// Adds the mass equations (27) of the element's nodes with in_ib[I] set (u, r node-major).
template <class E, class S>
void add_inactive_mass_residual(const Eigen::Matrix<double, E::kNodes, 1>& node_mass, const bool* in_ib,
                                const S* u, S* r) {
  constexpr int D = E::kDim;
  for (int I = 0; I < E::kNodes; ++I)
    if (in_ib[I])
      for (int i = 0; i < D; ++i) r[I * D + i] += node_mass[I] * u[I * D + i];
}

}  // namespace matpoint::implicit
