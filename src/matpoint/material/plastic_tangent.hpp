// The Kirchhoff stress of a Hencky plastic model (hencky_plasticity.hpp) as a function of the
// deformation gradient alone, with its exact derivative d tau / d F: what an implicit residual needs
// (the stored state C_p^-1, eps_p stays that of the last converged step during Newton's iterations,
// and Newton's quadratic convergence needs the derivative of this very map, the consistent tangent).
//
// tau(F) = sum_A tau_A(eps^trial) n_A (x) n_A,  eps^trial = 1/2 ln b,  b = F C_p^-1 F^T,
// with tau_A the model's return map. In the frame of b's eigenvectors n_A (eigenvalues x_A =
// exp(2 eps_A)), a change dF gives db = dF G + (dF G)^T with G = C_p^-1 F^T, and (Daleckii-Krein
// for the isotropic tensor functions ln and tau; de Souza Neto, Peric & Owen 2008 §A.5; Miehe 1998):
//   d tau~_AA = sum_B T_AB d eps_B,  d eps_B = db~_BB / (2 x_B)            (T: d tau_A / d eps_B^trial)
//   d tau~_AB = (tau_A - tau_B) / (x_A - x_B) db~_AB                        (A != B)
//             -> (T_AA - T_AB) / (2 x_A) db~_AB  when x_A = x_B (the limit of the same quotient),
// with db~ = Q^T db Q and d tau = Q d tau~ Q^T (Q = [n_1 n_2 n_3]). The elastic branch (T = D) is the
// derivative of the Hencky hyperelastic stress. Checked against central differences of tau(F) in
// tests/unit/test_plastic_tangent.cpp for every return region of the three models.
#pragma once

#include <algorithm>
#include <cmath>

#include "matpoint/core/dual.hpp"
#include "matpoint/material/hencky_plasticity.hpp"

namespace matpoint {

struct PlasticResponse {
  Mat3 tau;         // Kirchhoff stress
  Tensor4 dtau_dF;  // d tau_ij / d F_kl: row 3 i + j, column 3 k + l
  YieldState state = YieldState::Elastic;
};

/// tau(F) from the stored state (not advanced) and, unless `derivative` is false, its derivative.
/// F: 3 x 3 (embed3 for 2-D); dt: the step (rate-dependent yield stresses; 0: off).
template <class Yield>
[[nodiscard]] PlasticResponse hencky_plastic_response(const HenckyElasticity& elastic, const Yield& yield,
                                                      const Mat3& F, const double* state,
                                                      bool derivative = true, double dt = 0.0) {
  const Mat3 Cp_inv = plastic_metric(state);
  const Spectral trial = hencky_strain(F * Cp_inv * F.transpose());
  const PrincipalReturn r =
      yield.return_map(elastic, elastic.stress(trial.eps), state[kEquivalentPlasticStrain], dt);
  PlasticResponse out{from_principal(r.tau, trial.axes), Tensor4::Zero(), r.state};
  if (!derivative) return out;

  const Mat3& Q = trial.axes;
  const Vec3 x = (2.0 * trial.eps).array().exp().matrix();  // eigenvalues of b
  Mat3 shear = Mat3::Zero();                                // d tau~_AB / db~_AB, A != B
  for (int A = 0; A < 3; ++A)
    for (int B = 0; B < 3; ++B) {
      if (A == B) continue;
      const double gap = x[A] - x[B];
      shear(A, B) = std::abs(gap) > 1e-8 * std::max(x[A], x[B])
                        ? (r.tau[A] - r.tau[B]) / gap
                        : (r.tangent(A, A) - r.tangent(A, B)) / (2.0 * x[A]);
    }
  const Mat3 G = Cp_inv * F.transpose();
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      // dF = e_k (x) e_l: dF G has row k equal to G's row l.
      Mat3 dFG = Mat3::Zero();
      dFG.row(k) = G.row(l);
      const Mat3 db = Q.transpose() * (dFG + dFG.transpose()) * Q;
      Vec3 deps;
      for (int A = 0; A < 3; ++A) deps[A] = db(A, A) / (2.0 * x[A]);
      Mat3 dtau = shear.cwiseProduct(db);
      dtau.diagonal() = r.tangent * deps;
      const Mat3 dtau_cartesian = Q * dtau * Q.transpose();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.dtau_dF(3 * i + j, 3 * k + l) = dtau_cartesian(i, j);
    }
  return out;
}

/// The in-plane (D x D) Kirchhoff stress of a response as scalar S at F: for S = double its value;
/// for a dual number also its derivatives through the chain rule, d tau_ij = sum_kl dtau_ij/dF_kl dF_kl
/// (only the D x D block of F varies: F_zz = 1 in plane strain).
template <class S, int D>
[[nodiscard]] Eigen::Matrix<S, D, D> kirchhoff_of(const PlasticResponse& response,
                                                  const Eigen::Matrix<S, D, D>& F) {
  Eigen::Matrix<S, D, D> tau;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      S t(response.tau(i, j));
      if constexpr (!std::is_same_v<S, double>)
        for (int k = 0; k < D; ++k)
          for (int l = 0; l < D; ++l) {
            const double c = response.dtau_dF(3 * i + j, 3 * k + l);
            if (c != 0.0)
              for (std::size_t s = 0; s < t.d.size(); ++s) t.d[s] += c * F(k, l).d[s];
          }
      tau(i, j) = t;
    }
  return tau;
}

}  // namespace matpoint
