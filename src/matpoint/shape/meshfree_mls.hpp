// Moving least-squares (MLS) shape functions of the Galerkin meshfree method (Iaconeta et al. 2017
// §4.2.1, eqs. (50)-(58); extraction §6.2, A6), values and gradients at one point x from its cloud:
//
//   N_I(x) = P^T(x) M^-1(x) P_I W_I(x),   M(x) = sum_I P_I P_I^T W_I(x)                 (54), (55)
//
// with a Gaussian weight of dilation R_eff on the cloud r = |x - x_I| < R (the paper gives no weight;
// extraction §6.2). Two forms, in s = (r / R_eff)^2, s_R = (R / R_eff)^2:
//   truncated (the authors' code):  W = exp(-s), cut off at R: W jumps by exp(-s_R) (0.018 for
//     R = 2 R_eff) when a node enters or leaves the cloud, and grad W by 2 sqrt(s_R) exp(-s_R) / R_eff;
//   smooth (our default):  W = exp(-s) - exp(-s_R) (1 + s_R - s), the Gaussian minus its tangent in
//     s at s_R: W and grad W vanish at R (C1), W > 0 inside (exp(-s) is convex), so N_I and grad N_I,
//     hence F and the internal forces, change continuously as points move across clouds. The
//     truncated form's jumps inject energy in dynamic runs (docs/theory/implicit.md).
//
// with the linear basis P(y) = [1, (y - x)/R_eff], centred at the evaluation point and scaled by
// the dilation (the idea of shape/mls.hpp; identical in exact arithmetic to the paper's absolute
// basis, far better conditioned). The centre is held fixed while differentiating, so
// grad P(x) = [0; 1/R_eff] and (extraction §6.2)
//
//   grad N_I = [grad P^T M^-1 - P^T M^-1 (grad M) M^-1] P_I W_I + P^T M^-1 P_I grad W_I.
//
// The paper's kernel factor 1/(pi R_eff^2) cancels in N_I (it scales M and W alike) and is left out.
// Within one step the cloud is fixed.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <span>

#include "matpoint/core/types.hpp"
#include "matpoint/shape/meshfree_status.hpp"

namespace matpoint {

/// det M below this times M_11^(D+1) counts as singular (the criterion of shape/mls.hpp); the
/// basis is then the constant one (Shepard functions), as in the authors' code (extraction §6.2).
inline constexpr double kMlsSingularDeterminant = 1e-12;

/// The MLS weight's form (see the top of this file).
enum class MlsWeight : std::uint8_t { Smooth, Truncated };

/// The weight of a node at y_I = (x_I - x) / R_eff and its gradient with respect to x, for the cut
/// s_R = (R / R_eff)^2 (unused by the truncated form). Zero outside the cut.
template <int D>
double mls_weight(MlsWeight form, const Vec<D>& y, double s_cut, double inv_dilation, Vec<D>& gradient) {
  const double s = y.squaredNorm(), e = std::exp(-s);
  if (form == MlsWeight::Truncated) {
    gradient = (2.0 * e * inv_dilation) * y;  // d/dx exp(-|x - x_I|^2 / R_eff^2)
    return e;
  }
  if (!(s < s_cut)) {
    gradient.setZero();
    return 0.0;
  }
  const double e_cut = std::exp(-s_cut);
  gradient = (2.0 * (e - e_cut) * inv_dilation) * y;  // dW/ds = e_cut - exp(-s), ds/dx = -2 y / R_eff
  return e - e_cut * (1.0 + s_cut - s);
}

/// Shepard functions N_I = W_I / sum W and their gradients, from the weights w and gradients dw
/// already stored in N and dN.
template <int D>
MeshfreeStatus shepard_from_weights(std::span<double> N, std::span<Vec<D>> dN) {
  double sum_w = 0.0;
  Vec<D> sum_dw = Vec<D>::Zero();
  for (std::size_t i = 0; i < N.size(); ++i) sum_w += N[i], sum_dw += dN[i];
  if (!(sum_w > 0.0)) return MeshfreeStatus::Empty;
  for (std::size_t i = 0; i < N.size(); ++i) {
    dN[i] = dN[i] / sum_w - (N[i] / (sum_w * sum_w)) * sum_dw;
    N[i] /= sum_w;
  }
  return MeshfreeStatus::Shepard;
}

/// MLS shape functions N[i] = N_I(x) and gradients dN[i] for the cloud nodes[i] (eqs. (54)-(58)),
/// with dilation R_eff and, for the smooth weight, the cut radius R. Returns Ok, Shepard (moment
/// matrix singular: fewer than D + 1 nodes in general position) or Empty (no weight at all).
template <int D>
MeshfreeStatus mls_shape_functions(const Vec<D>& x, std::span<const Vec<D>> nodes, double dilation,
                                   std::span<double> N, std::span<Vec<D>> dN, MlsWeight form, double radius) {
  using Basis = Eigen::Matrix<double, D + 1, 1>;
  using Moment = Eigen::Matrix<double, D + 1, D + 1>;
  const double inv_s = 1.0 / dilation, s_cut = (radius * inv_s) * (radius * inv_s);
  Moment M = Moment::Zero();
  std::array<Moment, D> dM;
  for (auto& m : dM) m.setZero();
  // Pass 1: weights W_I, their gradients, M and grad M (eq. (55)); W and grad W are kept in N, dN.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    Basis P;
    P[0] = 1.0;
    P.template tail<D>() = (nodes[i] - x) * inv_s;
    const double w = mls_weight<D>(form, P.template tail<D>(), s_cut, inv_s, dN[i]);
    N[i] = w;
    const Moment PP = P * P.transpose();
    M.noalias() += w * PP;
    for (int k = 0; k < D; ++k) dM[k].noalias() += dN[i][k] * PP;
  }
  if (!(M(0, 0) > 0.0)) return MeshfreeStatus::Empty;
  if (!(std::abs(M.determinant()) >= kMlsSingularDeterminant * std::pow(M(0, 0), D + 1)))
    return shepard_from_weights<D>(N, dN);
  const Moment Minv = M.inverse();
  const Basis c = Minv.col(0);        // M^-1 P(x), P(x) = e_1
  Eigen::Matrix<double, D + 1, D> g;  // column k: M^-1 d_k P(x) - M^-1 (d_k M) M^-1 P(x)
  for (int k = 0; k < D; ++k) g.col(k) = Minv.col(k + 1) * inv_s - Minv * (dM[k] * c);
  // Pass 2: N_I = c . P_I W_I and its gradient.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    Basis P;
    P[0] = 1.0;
    P.template tail<D>() = (nodes[i] - x) * inv_s;
    const double cP = c.dot(P);
    dN[i] = N[i] * (g.transpose() * P) + cP * dN[i];
    N[i] *= cP;
  }
  return MeshfreeStatus::Ok;
}

}  // namespace matpoint
