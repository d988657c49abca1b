// One material point's residual and Jacobian in the Galerkin meshfree method (Iaconeta et al. 2017
// §4.2, Algorithm 2 step 2: "identical to MPM", with the point's cloud as its connectivity). The
// updated-Lagrangian residual of a point with cloud nodes I (the same terms as the implicit UL MPM,
// extraction §2-§4, with the consistent mass):
//
//   r_I = m_p (a_p - b) N_I + V0_p tau_p H^-T grad_n N_I,      H = 1 + sum_I du_I (x) grad_n N_I,
//   a_p = c sum_I N_I du_I + known_p,   F_p = H F_p^n,   tau_p = tau(F_p)  (the material's law),
//
// with grad_n the gradient in the step-start configuration x^n. A cloud holds 10-100 nodes, so the
// AD of implicit/ad_jacobian.hpp over all its dofs would be wasteful: the residual depends on the
// dofs only through z = (H, u_p) (D^2 + D numbers), r = B^T f(z) with B linear, so f and df/dz are
// taken by AD on Dual<D^2 + D> and the block Jacobian is K = B^T (df/dz) B (exact, by the chain rule).
#pragma once

#include <Eigen/Dense>
#include <span>

#include "matpoint/core/dual.hpp"
#include "matpoint/core/types.hpp"
#include "matpoint/implicit/implicit_material.hpp"

namespace matpoint::implicit {

/// What a point's residual needs that stays fixed during one step's Newton iterations.
template <int D>
struct MeshfreePointData {
  std::span<const double> N;  // N_I(x_p^n) of the cloud
  std::span<const Vec<D>> G;  // grad_n N_I(x_p^n)
  double mass = 0.0, volume0 = 0.0;
  Mat<D> F_old = Mat<D>::Identity();
  Vec<D> known_minus_b = Vec<D>::Zero();  // a_p without the c u_p term, minus the body force
  double inertia_coefficient = 0.0;       // c = 1 / (beta dt^2); 0: quasi-static
  const double* state = nullptr;          // material history of the step start
  double dt = 0.0;
};

namespace meshfree_residual_detail {

/// f(z) = [P = V0 tau(H F^n) H^-T (row-major), m (c u_p + known - b)] on any scalar.
template <int D, class S, class Material>
Eigen::Matrix<S, D * D + D, 1> point_forces(const MeshfreePointData<D>& q, const Material& material,
                                            const Eigen::Matrix<S, D, D>& H,
                                            const Eigen::Matrix<S, D, 1>& up) {
  using MatS = Eigen::Matrix<S, D, D>;
  const MatS F = H * q.F_old;
  const MatS tau = kirchhoff_stress_of<S, D>(material, F, q.state, q.dt);
  const MatS P = q.volume0 * (tau * H.inverse().transpose());
  Eigen::Matrix<S, D * D + D, 1> f;
  for (int i = 0; i < D; ++i) {
    for (int j = 0; j < D; ++j) f[i * D + j] = P(i, j);
    f[D * D + i] = q.mass * (q.inertia_coefficient * up[i] + q.known_minus_b[i]);
  }
  return f;
}

}  // namespace meshfree_residual_detail

/// r (n D) and, when K is not null, K (row-major n D x n D) of one point for its cloud's dof
/// increments du (node-major, D per node). Both are overwritten.
template <int D, class Material>
void meshfree_point_residual(const MeshfreePointData<D>& q, const Material& material, const double* du,
                             double* r, double* K) {
  constexpr int Z = D * D + D;
  using S = Dual<Z>;
  const std::size_t n = q.N.size();
  // z at du, seeded as the AD variables.
  Mat<D> H = Mat<D>::Identity();
  Vec<D> up = Vec<D>::Zero();
  for (std::size_t I = 0; I < n; ++I)
    for (int i = 0; i < D; ++i) {
      up[i] += q.N[I] * du[I * D + i];
      for (int j = 0; j < D; ++j) H(i, j) += du[I * D + i] * q.G[I][j];
    }
  Eigen::Matrix<S, D, D> Hs;
  Eigen::Matrix<S, D, 1> us;
  for (int i = 0; i < D; ++i) {
    for (int j = 0; j < D; ++j) Hs(i, j) = S::variable(H(i, j), i * D + j);
    us[i] = S::variable(up[i], D * D + i);
  }
  const auto f = meshfree_residual_detail::point_forces<D, S>(q, material, Hs, us);
  Eigen::Matrix<double, Z, 1> fv;
  Eigen::Matrix<double, Z, Z> dfdz;
  for (int a = 0; a < Z; ++a) {
    fv[a] = f[a].v;
    for (int b = 0; b < Z; ++b) dfdz(a, b) = f[a].d[static_cast<std::size_t>(b)];
  }
  // r_Ii = f_u,i N_I + sum_j P_ij G_Ij, i.e. r_Ii = B_Ii . f with B_Ii = d z / d du_Ii.
  auto b_row = [&](std::size_t I, int i) {
    Eigen::Matrix<double, Z, 1> b = Eigen::Matrix<double, Z, 1>::Zero();
    for (int j = 0; j < D; ++j) b[i * D + j] = q.G[I][j];
    b[D * D + i] = q.N[I];
    return b;
  };
  for (std::size_t I = 0; I < n; ++I)
    for (int i = 0; i < D; ++i) r[I * D + i] = b_row(I, i).dot(fv);
  if (K == nullptr) return;
  // K = B^T (df/dz) B: first C = (df/dz) B column by column, then rows.
  const std::size_t m = n * D;
  Eigen::Matrix<double, Z, Eigen::Dynamic> C(Z, m), B(Z, m);
  for (std::size_t I = 0; I < n; ++I)
    for (int i = 0; i < D; ++i) B.col(static_cast<Eigen::Index>(I * D + i)) = b_row(I, i);
  C.noalias() = dfdz * B;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Km(
      K, static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  Km.noalias() = B.transpose() * C;
}

}  // namespace matpoint::implicit
