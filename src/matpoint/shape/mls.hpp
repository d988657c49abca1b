// Reconstruction of a field at a point from scattered data (Gong 2015 ch. 3; extraction §2):
//   Shepard ("first-order MLS"):  u^h(x) = sum_p w(x - x_p) u_p / sum_p w(x - x_p), the mapping of
//                                 lumped-mass MPM (§4.3.1);
//   MLS with a linear basis ("second-order MLS", the IMPM reconstruction of ch. 5):
//                                 u^h(x) = P^T(x) M^-1(x) sum_p w(x - x_p) P(x_p) u_p      (3.16)
//                                 M(x) = sum_p w(x - x_p) P(x_p) P^T(x_p).
// The basis is centred and scaled at the evaluation point, P(y) = [1, (y - x)/h], so u^h(x) is the
// first component of the solution (extraction §2.2, "implementation form"): shift invariant and
// better conditioned than (3.16) as printed, and identical in exact arithmetic. Weights are tensor
// products of a 1-D kernel of |x - x_p| / h (extraction §4.2).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// Hat kernel of radius h (the MPM shape function, Gong eq. (4.8)); q = |x - x_p| / h.
inline double hat_weight(double q) { return q < 1.0 ? 1.0 - q : 0.0; }

/// Cubic B-spline of radius 2h (Gong eq. (5.1) in q = |x - x_p| / h): the IMPM velocity weight.
inline double cubic_weight(double q) {
  if (q <= 1.0) return 2.0 / 3.0 - q * q + 0.5 * q * q * q;
  if (q <= 2.0) return (2.0 - q) * (2.0 - q) * (2.0 - q) / 6.0;
  return 0.0;
}

/// Quadratic B-spline of radius 1.5h (Gong eq. (5.2)): the IMPM density, stress and body-force weight.
inline double quadratic_weight(double q) {
  if (q <= 0.5) return 0.75 - q * q;
  if (q <= 1.5) return 0.5 * (1.5 - q) * (1.5 - q);
  return 0.0;
}

/// How a reconstruction at one point was obtained.
enum class MlsStatus { Fit, Shepard, Empty };  // the asked degree; Shepard fallback; no data (0/0)

/// The weighted sums of an MLS fit of K fields at one point x (Gong 2015 (3.12)-(3.16)) with the
/// centred, scaled basis P = [1, (x_p - x)/h] (extraction §2.2): M = sum w P P^T, R = sum w P u^T.
/// The fitted value is the first row of M^-1 R.
template <int D, int K>
struct MlsSums {
  using Values = Eigen::Matrix<double, K, 1>;
  Eigen::Matrix<double, D + 1, D + 1> moment = Eigen::Matrix<double, D + 1, D + 1>::Zero();
  Eigen::Matrix<double, D + 1, K> rhs = Eigen::Matrix<double, D + 1, K>::Zero();

  /// Adds a point with weight w, scaled offset d = (x_p - x)/h and values u.
  void add(double w, const Vec<D>& d, const Values& u) {
    Eigen::Matrix<double, D + 1, 1> basis;
    basis[0] = 1.0;
    basis.template tail<D>() = d;
    moment.noalias() += (w * basis) * basis.transpose();
    rhs.noalias() += (w * basis) * u.transpose();
  }

  /// The reconstruction with the linear basis (degree 1) or Shepard (degree 0). A moment matrix with
  /// det M < 1e-12 M_11^(D+1) (extraction A16) falls back to Shepard; no weight at all: Empty.
  MlsStatus solve(int degree, Values& out) const {
    const double m11 = moment(0, 0);
    if (!(m11 > 0.0)) {
      out.setZero();
      return MlsStatus::Empty;
    }
    if (degree >= 1 && std::abs(moment.determinant()) >= 1e-12 * std::pow(m11, D + 1)) {
      const Eigen::Matrix<double, D + 1, 1> c = moment.inverse().col(0);  // M c = e_1 (M symmetric)
      out = rhs.transpose() * c;
      return MlsStatus::Fit;
    }
    out = rhs.row(0).transpose() / m11;
    return degree >= 1 ? MlsStatus::Shepard : MlsStatus::Fit;
  }
};

template <int D, class Kernel>
double tensor_weight(const Vec<D>& x, const Vec<D>& xp, double h, Kernel&& kernel) {
  double w = 1.0;
  for (int a = 0; a < D; ++a) w *= kernel(std::abs(x[a] - xp[a]) / h);
  return w;
}

/// Shepard reconstruction at x; nothing when no point lies in the kernel's support (0/0).
template <int D, class Kernel>
std::optional<double> shepard(const Vec<D>& x, const std::vector<Vec<D>>& points,
                              const std::vector<double>& values, double h, Kernel&& kernel) {
  double sum_w = 0.0, sum_wu = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double w = tensor_weight<D>(x, points[p], h, kernel);
    sum_w += w;
    sum_wu += w * values[p];
  }
  if (!(sum_w > 0.0)) return std::nullopt;
  return sum_wu / sum_w;
}

/// MLS with the linear basis at x; nothing when the moment matrix is singular (fewer than D + 1
/// points in general position within the support).
template <int D, class Kernel>
std::optional<double> mls_linear(const Vec<D>& x, const std::vector<Vec<D>>& points,
                                 const std::vector<double>& values, double h, Kernel&& kernel) {
  using Basis = Eigen::Matrix<double, D + 1, 1>;
  Eigen::Matrix<double, D + 1, D + 1> moment = Eigen::Matrix<double, D + 1, D + 1>::Zero();
  Basis rhs = Basis::Zero();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double w = tensor_weight<D>(x, points[p], h, kernel);
    if (w == 0.0) continue;
    Basis basis;
    basis[0] = 1.0;
    for (int a = 0; a < D; ++a) basis[a + 1] = (points[p][a] - x[a]) / h;
    moment += w * basis * basis.transpose();
    rhs += w * values[p] * basis;
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, D + 1, D + 1>> lu(moment);
  if (!lu.isInvertible()) return std::nullopt;
  return lu.solve(rhs)[0];
}

}  // namespace matpoint
