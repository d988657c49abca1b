// Particle contribution to the element residual (Aulisa & Capodaglio eqs. (20)-(25), in the
// consistent form of the extraction's A1):
//   r_I += m_p (a_p - b_p) N_I(xi_p) + V0_p tau_p grad_x N_I(xi_p)
//   a_p = u~_g(x_p) / (beta dt^2) - v_p^n / (beta dt) - (1 - 2 beta) / (2 beta) a_p^n         (21), (22)
//   F_p = (I + grad~ u~*) F_p^n                                                                (24), (25)
//   grad_x N_I = H^-T grad~ N_I,  H = I + grad~ u~*  (the current nodes x~ + u~*)              (A24)
// or, with small_strain (a geometrically linear check, e.g. the cantilever against Timoshenko):
//   r_I += m_p (a_p - b_p) N_I + V0_p sigma_p grad~ N_I,  sigma = lambda tr(eps) 1 + 2 mu eps,
//   eps = sym(F_p - 1), F_p = F_p^n + grad~ u~ (additive: the strains of the steps add up, the
//   geometrically linear kinematics on the fixed reference mesh),
// with u~* the receding-corrected displacements (receding_contact.hpp) for a switched particle
// and u~ itself otherwise; the inertia always uses the uncorrected u~ (extraction §8). Written once
// on the scalar type S: double for a residual, Dual<N> for the residual and its Jacobian.
#pragma once

#include <algorithm>
#include <array>

#include "matpoint/core/dual.hpp"
#include "matpoint/implicit/implicit_material.hpp"
#include "matpoint/implicit/particle_newmark/particle_quadrature.hpp"
#include "matpoint/implicit/particle_newmark/receding_contact.hpp"

namespace matpoint::implicit {

struct ParticleResidualOptions {
  double inertia_coefficient = 0.0;  // 1 / (beta dt^2): a_p = inertia_coefficient u~_p + known
  /// A24: the current-configuration gradients from the corrected nodes x~ + u~* (the authors'
  /// code; default) or from the uncorrected x~ + u~.
  bool receding_in_gradient = true;
  bool small_strain = false;  // Hooke's law on sym(F - 1), reference gradients (see above)
  double dt = 0.0;            // the step (rate-dependent yield stresses)
};

/// r_I += m_p (a_p - b_p) N_I + P grad~ N_I for particle p, with a_p from (21) on the uncorrected
/// u~_p = sum_I N_I u~_I and P the stress term per unit reference gradient.
template <class E, class S>
void add_inertia_and_stress(const ParticleQuadrature<E>& q, Index p, const ParticleResidualOptions& options,
                            const S* u, const Eigen::Matrix<S, E::kDim, E::kDim>& P, S* r) {
  constexpr int n = E::kNodes, D = E::kDim;
  const auto& N = q.N[static_cast<std::size_t>(p)];
  const auto& G = q.G[static_cast<std::size_t>(p)];
  const double m = q.mass[static_cast<std::size_t>(p)];
  const auto& known = q.known[static_cast<std::size_t>(p)];
  std::array<S, D> inertia;
  for (int i = 0; i < D; ++i) {
    S up = N[0] * u[i];
    for (int I = 1; I < n; ++I) add_product(up, u[I * D + i], N[I]);
    inertia[static_cast<std::size_t>(i)] = m * (options.inertia_coefficient * up + known[i]);
  }
  for (int I = 0; I < n; ++I)
    for (int i = 0; i < D; ++i) {
      add_product(r[I * D + i], inertia[static_cast<std::size_t>(i)], N[I]);
      for (int j = 0; j < D; ++j) add_product(r[I * D + i], P(i, j), G(I, j));
    }
}

/// Adds the contributions of the particles [first, last) of q (all in one element) to r.
/// u and r: the element's nodal displacement increments and residual, node-major (D per node).
template <class E, class Material, class S>
void add_particle_residual(const ParticleQuadrature<E>& q, Index first, Index last, const Material* materials,
                           const FaceCoefficients<E>& receding_coefficient,
                           const ParticleResidualOptions& options, const S* u, S* r) {
  constexpr int n = E::kNodes, D = E::kDim;
  using MatS = Eigen::Matrix<S, D, D>;
  std::array<S, n * D> corrected;
  for (Index p = first; p < last; ++p) {
    const auto& G = q.G[static_cast<std::size_t>(p)];
    const std::uint32_t switches = q.receding[static_cast<std::size_t>(p)];
    const S* us = u;
    if constexpr (RecedingStencil<E>::kSupported) {
      if (switches != 0) {
        std::copy(u, u + n * D, corrected.begin());
        apply_receding_correction<E>(switches, receding_coefficient, corrected.data());
        us = corrected.data();
      }
    }
    // H = I + grad~ u~* (25); H_ij = delta_ij + sum_I u*_Ii dN_I/dx~_j.
    MatS H = MatS::Identity();
    for (int I = 0; I < n; ++I)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) add_product(H(i, j), us[I * D + i], G(I, j));
    const Material& material = materials[q.material[static_cast<std::size_t>(p)]];
    if (options.small_strain) {
      MatS F = H;  // F^n + grad~ u~
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
          F(i, j) += q.F_old[static_cast<std::size_t>(p)](i, j) - (i == j ? 1.0 : 0.0);
      const MatS eps = 0.5 * (F + F.transpose()) - MatS::Identity();
      const MatS sigma = (material.lambda * eps.trace()) * MatS::Identity() + (2.0 * material.mu) * eps;
      add_inertia_and_stress(q, p, options, u, MatS(q.volume0[static_cast<std::size_t>(p)] * sigma), r);
      continue;
    }
    const MatS F = H * q.F_old[static_cast<std::size_t>(p)];  // (24)
    const MatS tau = kirchhoff_stress_of<S, D>(material, F, q.state[static_cast<std::size_t>(p)], options.dt);
    MatS H_gradient = H;
    if (switches != 0 && !options.receding_in_gradient) {
      H_gradient = MatS::Identity();
      for (int I = 0; I < n; ++I)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) add_product(H_gradient(i, j), u[I * D + i], G(I, j));
    }
    // V0 tau grad_x N_I = V0 (tau H^-T) grad~ N_I: P~ = V0 tau H^-T once per particle.
    add_inertia_and_stress(
        q, p, options, u,
        MatS(q.volume0[static_cast<std::size_t>(p)] * (tau * H_gradient.inverse().transpose())), r);
  }
}

}  // namespace matpoint::implicit
