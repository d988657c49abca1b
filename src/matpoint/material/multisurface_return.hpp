// The return map onto an intersection of planes in principal Kirchhoff stress space (tension
// positive, tau_1 >= tau_2 >= tau_3), for perfectly plastic surfaces f_i = a_i . tau - b_i <= 0 with
// plastic potentials g_i = g_i . tau (non-associated when g_i != a_i) and Koiter's rule at corners:
//   tau = tau^trial - D sum_{i in A} dlambda_i g_i,   f_j(tau) = 0 for j in A,   dlambda_i >= 0,
// so for an active set A (matrices A = [a_j], G = [g_i]) dlambda = (A^T D G)^-1 (A^T tau^trial - b).
// Every set of one to three planes is tried; the return is the admissible one (dlambda >= 0, every
// f <= 0, the order tau_1 >= tau_2 >= tau_3 kept) with the fewest active planes, then the nearest in
// the complementary-energy norm |tau - tau^trial|_{D^-1}. Its consistent tangent in the principal
// frame is d tau / d eps^trial = (I - D G (A^T D G)^-1 A^T) D (de Souza Neto, Peric & Owen 2008 §8.2,
// the multi-surface return of Box 8.5 for linear surfaces). Used by Mohr-Coulomb with a tension
// cut-off (mohr_coulomb.hpp), where the closed form of the pyramid alone no longer applies.
#pragma once

#include <Eigen/LU>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

#include "matpoint/material/hencky_plasticity.hpp"

namespace matpoint {

struct YieldPlane {
  Vec3 normal;  // a: f = a . tau - offset
  double offset;
  Vec3 flow;  // g: the plastic strain direction
};

/// The return onto the planes (at most 8); the trial state itself (Elastic) when it is admissible.
/// `scale`: a stress of the problem's size, for the tolerances. For planes whose intersection is a
/// non-empty convex set one of the sets is admissible.
[[nodiscard]] inline PrincipalReturn multisurface_return(const HenckyElasticity& elastic,
                                                         std::span<const YieldPlane> planes,
                                                         const Vec3& trial, double scale) {
  const Mat3 D = elastic.matrix();
  const double tolerance = 1e-10 * (scale + trial.cwiseAbs().maxCoeff());
  const auto admissible = [&](const Vec3& tau) {
    for (const YieldPlane& p : planes)
      if (p.normal.dot(tau) - p.offset > tolerance) return false;
    return tau[0] >= tau[1] - tolerance && tau[1] >= tau[2] - tolerance;
  };
  PrincipalReturn best{trial, D, 0.0, YieldState::Elastic};
  if (admissible(trial)) return best;
  const Mat3 D_inv = D.inverse();
  int best_count = 4;
  double best_distance = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(planes.size());
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    const int count = std::popcount(mask);
    if (count > 3 || count > best_count) continue;
    Eigen::Matrix<double, 3, Eigen::Dynamic> A(3, count), G(3, count);
    Eigen::VectorXd b(count);
    for (int i = 0, c = 0; i < n; ++i)
      if (mask >> i & 1u) {
        A.col(c) = planes[static_cast<std::size_t>(i)].normal;
        G.col(c) = planes[static_cast<std::size_t>(i)].flow;
        b[c++] = planes[static_cast<std::size_t>(i)].offset;
      }
    const Eigen::MatrixXd M = A.transpose() * D * G;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
    if (lu.rank() < count) continue;
    const Eigen::VectorXd dlambda = lu.solve(A.transpose() * trial - b);
    if (dlambda.minCoeff() < -1e-12 * (1.0 + dlambda.cwiseAbs().maxCoeff())) continue;
    const Vec3 tau = trial - D * G * dlambda;
    if (!admissible(tau)) continue;
    const double distance = (tau - trial).dot(D_inv * (tau - trial));
    if (count == best_count && distance >= best_distance) continue;
    best_count = count;
    best_distance = distance;
    best.tau = tau;
    best.tangent = (Mat3::Identity() - D * G * lu.inverse() * A.transpose()) * D;
    best.state = count == 1 ? YieldState::Surface : count == 2 ? YieldState::Edge : YieldState::Apex;
  }
  return best;
}

}  // namespace matpoint
