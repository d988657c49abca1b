// Multiplicative finite-strain plasticity with Hencky (logarithmic) elastic strains: the frame the
// plastic models share (mohr_coulomb.hpp, drucker_prager.hpp, von_mises.hpp; docs/theory/plasticity.md).
//
// Kinematics (Iaconeta et al. 2017 §7.2 after Clausen et al. 2006/2007; Simo 1992; de Souza Neto,
// Peric & Owen 2008 §14.3): F = F_e F_p and b_e = F_e F_e^T = F C_p^-1 F^T, C_p^-1 = F_p^-1 F_p^-T.
// With F_{n+1} = f F_n the paper's trial state f b_e^n f^T equals F_{n+1} C_p,n^-1 F_{n+1}^T, so the
// stress is a function of the current F and the stored C_p^-1 only (no F_n: what an implicit
// residual needs, and what a checkpoint carries).
//   eps^trial = 1/2 ln b_e^trial = sum_A eps_A n_A (x) n_A                   (Hencky strain)
//   tau_A^trial = D_AB eps_B^trial,  D_AB = lambda + 2 mu delta_AB            (Kirchhoff, principal)
//   tau_A = the model's return map in principal space (tension positive, tau_1 >= tau_2 >= tau_3)
//   eps_e,A = D^-1 tau_A,  b_e = sum_A exp(2 eps_e,A) n_A (x) n_A              (exponential return)
//   C_p^-1 <- F^-1 b_e F^-T,   tau = sum_A tau_A n_A (x) n_A,   sigma = tau / J
// 2-D is plane strain (F_zz = 1; b_e and tau are 3x3, and sigma_zz is kept), 1-D uniaxial strain.
//
// History per particle, kPlasticStateSize = 9 doubles:
//   [0..5] C_p^-1 - I in the order xx, yy, zz, xy, yz, xz   (all zero: the virgin material)
//   [6]    equivalent plastic strain (each model states its definition)
//   [7]    yield state of the last update (YieldState: 0 elastic, 1 surface, 2 edge, 3 apex)
//   [8]    plastic work per unit reference volume: the sum over the returns of tau_A Delta eps_p,A
//          (returned principal Kirchhoff stress times the principal plastic log-strain increment
//          eps^trial - eps_e: backward Euler of the dissipation rate tau : d_p), so that
//          K + U + plastic work - W_ext is what the solver conserves
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
/// A fourth-order tensor C_ijkl as a 9 x 9 matrix, row 3 i + j, column 3 k + l.
using Tensor4 = Eigen::Matrix<double, 9, 9>;

/// Where the return map ended: the smooth surface (MC plane, DP cone, J2 cylinder), an edge of
/// the Mohr-Coulomb pyramid, or the apex of MC / DP.
enum class YieldState { Elastic = 0, Surface = 1, Edge = 2, Apex = 3 };

inline constexpr int kPlasticStateSize = 9;
inline constexpr int kEquivalentPlasticStrain = 6;
inline constexpr int kYieldState = 7;
inline constexpr int kPlasticWork = 8;

/// Isotropic Hencky elasticity in principal space: tau_A = D_AB eps_B, D_AB = lambda + 2 mu delta_AB.
struct HenckyElasticity {
  double lambda, mu;

  [[nodiscard]] double bulk_modulus() const { return lambda + 2.0 * mu / 3.0; }
  [[nodiscard]] Mat3 matrix() const { return lambda * Mat3::Ones() + 2.0 * mu * Mat3::Identity(); }
  [[nodiscard]] Vec3 stress(const Vec3& eps) const {
    return Vec3::Constant(lambda * eps.sum()) + 2.0 * mu * eps;
  }
  /// D^-1 tau = tau / (2 mu) - lambda tr(tau) / (2 mu (3 lambda + 2 mu)).
  [[nodiscard]] Vec3 strain(const Vec3& tau) const {
    return (tau - Vec3::Constant(lambda * tau.sum() / (3.0 * lambda + 2.0 * mu))) / (2.0 * mu);
  }
  /// Stored energy per unit reference volume, W = lambda/2 (tr eps)^2 + mu eps : eps.
  [[nodiscard]] double energy(const Vec3& eps) const {
    return 0.5 * lambda * eps.sum() * eps.sum() + mu * eps.squaredNorm();
  }
};

/// The result of a return map in principal space.
struct PrincipalReturn {
  Vec3 tau;      // returned principal Kirchhoff stresses, in the trial's (descending) order
  Mat3 tangent;  // d tau_A / d eps_B^trial: the consistent tangent in the principal frame
  double plastic_strain_increment = 0.0;
  YieldState state = YieldState::Elastic;
};

/// F of a D-dimensional problem as 3 x 3 (plane strain / uniaxial strain: 1 outside).
template <int D>
[[nodiscard]] Mat3 embed3(const Mat<D>& F) {
  Mat3 F3 = Mat3::Identity();
  F3.topLeftCorner<D, D>() = F;
  return F3;
}

/// C_p^-1 from the state (stored as C_p^-1 - I) and back.
[[nodiscard]] inline Mat3 plastic_metric(const double* s) {
  Mat3 m;
  m << 1.0 + s[0], s[3], s[5], s[3], 1.0 + s[1], s[4], s[5], s[4], 1.0 + s[2];
  return m;
}
inline void store_plastic_metric(const Mat3& m, double* s) {
  s[0] = m(0, 0) - 1.0;
  s[1] = m(1, 1) - 1.0;
  s[2] = m(2, 2) - 1.0;
  s[3] = 0.5 * (m(0, 1) + m(1, 0));
  s[4] = 0.5 * (m(1, 2) + m(2, 1));
  s[5] = 0.5 * (m(0, 2) + m(2, 0));
}

/// Principal Hencky strains eps_A = 1/2 ln(eig_A b), sorted so that eps_1 >= eps_2 >= eps_3, with
/// their axes as the columns of `axes`.
struct Spectral {
  Vec3 eps;
  Mat3 axes;
};
[[nodiscard]] inline Spectral hencky_strain(const Mat3& b) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(b);  // ascending eigenvalues
  Spectral s;
  for (int a = 0; a < 3; ++a) {
    s.eps[a] = 0.5 * std::log(eigen.eigenvalues()[2 - a]);
    s.axes.col(a) = eigen.eigenvectors().col(2 - a);
  }
  return s;
}

/// sum_A v_A n_A (x) n_A.
[[nodiscard]] inline Mat3 from_principal(const Vec3& v, const Mat3& axes) {
  return axes * v.asDiagonal() * axes.transpose();
}

/// The consistent tangent d tau / d eps^trial in Cartesian axes (log-strain space) of an isotropic
/// return map, from its principal tangent (Clausen et al. 2006 via the extraction §7.2.4; Miehe
/// 1998 for the spectral form):
///   C = sum_AB T_AB N_A (x) N_B + sum_{A != B} (tau_A - tau_B)/(eps_A - eps_B) N_AB (x) sym N_AB,
/// N_A = n_A (x) n_A, N_AB = n_A (x) n_B. The shear factor is Clausen's G T_ij written in strain;
/// for eps_A = eps_B its limit T_AA - T_AB is used.
[[nodiscard]] inline Tensor4 cartesian_tangent(const PrincipalReturn& r, const Spectral& trial) {
  Tensor4 C = Tensor4::Zero();
  const Mat3& n = trial.axes;
  auto add = [&](double factor, const Mat3& X, const Mat3& Y) {  // C += factor X (x) Y
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) C(3 * i + j, 3 * k + l) += factor * X(i, j) * Y(k, l);
  };
  for (int A = 0; A < 3; ++A)
    for (int B = 0; B < 3; ++B) {
      const Mat3 NA = n.col(A) * n.col(A).transpose();
      if (r.tangent(A, B) != 0.0) add(r.tangent(A, B), NA, n.col(B) * n.col(B).transpose());
      if (A == B) continue;
      const double gap = trial.eps[A] - trial.eps[B];
      const double shear = std::abs(gap) > 1e-12 * std::max(1.0, std::abs(trial.eps[A]))
                               ? (r.tau[A] - r.tau[B]) / gap
                               : r.tangent(A, A) - r.tangent(A, B);
      const Mat3 NAB = n.col(A) * n.col(B).transpose();
      add(0.5 * shear, NAB, NAB + NAB.transpose());
    }
  return C;
}

/// One stress update of a Hencky plastic model (Yield: the return map): the Kirchhoff stress at F
/// from the stored state, which it advances. Elastic steps leave C_p^-1 untouched. dt: the step's
/// duration, for rate-dependent yield stresses (0: rate terms off).
template <class Yield>
Mat3 hencky_plastic_update(const HenckyElasticity& elastic, const Yield& yield, const Mat3& F, double* state,
                           double dt = 0.0) {
  const Mat3 Cp_inv = plastic_metric(state);
  const Spectral trial = hencky_strain(F * Cp_inv * F.transpose());
  const PrincipalReturn r =
      yield.return_map(elastic, elastic.stress(trial.eps), state[kEquivalentPlasticStrain], dt);
  state[kYieldState] = static_cast<double>(r.state);
  if (r.state != YieldState::Elastic) {
    const Vec3 eps_e = elastic.strain(r.tau);
    const Mat3 b_e = from_principal((2.0 * eps_e).array().exp().matrix(), trial.axes);
    const Mat3 F_inv = F.inverse();
    store_plastic_metric(F_inv * b_e * F_inv.transpose(), state);
    state[kEquivalentPlasticStrain] += r.plastic_strain_increment;
    state[kPlasticWork] += r.tau.dot(trial.eps - eps_e);
  }
  return from_principal(r.tau, trial.axes);
}

/// A material made of Hencky elasticity and a yield surface with its return map.
template <class Yield>
struct HenckyPlastic {
  double density;
  HenckyElasticity elastic;
  Yield yield;

  static constexpr int state_size = kPlasticStateSize;

  /// Cauchy stress tau / J - q I at F (q: artificial viscosity); advances the state. sigma_zz is the
  /// out-of-plane component (plane strain). dt: the step (rate-dependent yield stresses; 0: off).
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double q, double* state, double& sigma_zz,
                              double dt = 0.0) const {
    const Mat3 tau = hencky_plastic_update(elastic, yield, embed3<D>(F), state, dt);
    const double J = F.determinant();
    sigma_zz = tau(2, 2) / J - q;
    return tau.topLeftCorner<D, D>() / J - q * Mat<D>::Identity();
  }
  /// Elastic stored energy per unit initial volume, W(eps_e) with b_e = F C_p^-1 F^T.
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& F, const double* state) const {
    const Mat3 F3 = embed3<D>(F);
    return elastic.energy(hencky_strain(F3 * plastic_metric(state) * F3.transpose()).eps);
  }
  /// Elastic dilatational speed sqrt((lambda + 2 mu) / rho): the plastic tangent is softer.
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return std::sqrt((elastic.lambda + 2.0 * elastic.mu) / density);
  }
};

}  // namespace matpoint
