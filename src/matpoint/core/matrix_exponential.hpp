// exp(A) for small fixed-size matrices: a Taylor polynomial of the degree the norm needs, with
// scaling and squaring only above a norm of 1/4.
#pragma once

#include <array>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

namespace matrix_exponential_detail {

/// theta[m - 1]: the largest infinity norm x of A for which the Taylor polynomial of degree m is
/// used, x^(m+1) / (m+1)! <= 1e-17 (the values are (1e-17 (m+1)!)^(1/(m+1)) rounded down).
/// Accuracy: for ||A|| = x <= theta_m the dropped terms sum to at most
///   sum_{k>m} x^k / k! <= x^(m+1) / (m+1)! * 1 / (1 - x / (m+2)) <= 1.1e-17   (x <= 1/4, m >= 1),
/// while ||exp(A)|| >= 1 / ||exp(-A)|| >= e^(-x) >= 0.77, so the truncation error is below 1.5e-17
/// relative, under a tenth of double's epsilon 2.2e-16: the polynomial is exp(A) to round-off. The
/// degree is the one the former term-by-term loop stopped at (it summed until the bound of the
/// next term, x^(k+1)/(k+1)!, fell below 1e-17), so the two agree to round-off. For the velocity
/// gradient increments of MPM (|L dt| ~ 1e-3) the degree is 4 or 5.
inline constexpr std::array<double, 12> kTaylorNormLimit{4.472e-9,  3.914e-6,  1.2446e-4, 1.0371e-3,
                                                         4.3942e-3, 1.2599e-2, 2.8228e-2, 5.3562e-2,
                                                         9.0360e-2, 0.13981,   0.20262,   0.27907};
/// 1/k! for the terms A^k / k!.
inline constexpr std::array<double, 13> kInverseFactorial{
    1.0,        1.0,         1.0 / 2,      1.0 / 6,       1.0 / 24,       1.0 / 120,      1.0 / 720,
    1.0 / 5040, 1.0 / 40320, 1.0 / 362880, 1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600};
/// Above this norm the argument is scaled by 2^-s into [0, 1/4] and the result squared s times.
inline constexpr double kScalingThreshold = 0.25;

/// sum_{k=0}^{m} A^k / k! for the smallest degree m <= 12 whose limit holds ||A|| (m = 12 for a
/// norm above 0.279 or not a number, which then propagates). The terms are added in the order of
/// k, as the former loop did; the powers come from two chains, A^(k+2) = A^k A^2 for odd and for
/// even k, so the dependent products are half as many as in A^k = A^(k-1) A.
template <int D>
Mat<D> taylor(const Mat<D>& A, double norm) {
  int m = 1;
  while (m < 12 && !(norm <= kTaylorNormLimit[static_cast<std::size_t>(m - 1)])) ++m;
  Mat<D> sum = A;
  sum.diagonal().array() += 1.0;
  if (m == 1) return sum;
  const Mat<D> A2 = A * A;
  sum += A2 * 0.5;
  Mat<D> even = A2, odd = A2 * A;  // A^k for the next even and odd k
  for (int k = 3; k <= m; k += 2) {
    sum += odd * kInverseFactorial[static_cast<std::size_t>(k)];
    if (k + 1 > m) break;
    even = even * A2;
    sum += even * kInverseFactorial[static_cast<std::size_t>(k + 1)];
    if (k + 2 <= m) odd = odd * A2;
  }
  return sum;
}

}  // namespace matrix_exponential_detail

/// exp(A), exact to round-off. For ||A||_inf <= 1/4 (the F update's L dt, a strain increment, is
/// far below) one Taylor polynomial and no scaling (see matrix_exponential_detail for the error
/// bound); above, the polynomial of A / 2^s with ||A / 2^s|| <= 1/4, squared s times.
template <int D>
Mat<D> matrix_exponential(const Mat<D>& A) {
  using namespace matrix_exponential_detail;
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();  // infinity norm
  if (!(norm > kScalingThreshold) || !std::isfinite(norm)) return taylor<D>(A, norm);
  int exponent = 0;  // norm / (1/4) = f 2^e, f in [1/2, 1): s = ceil(log2(4 norm))
  const double f = std::frexp(norm / kScalingThreshold, &exponent);
  const int squarings = f == 0.5 ? exponent - 1 : exponent;
  const double scale = std::ldexp(1.0, -squarings);  // exact: a power of two
  Mat<D> result = taylor<D>(A * scale, norm * scale);
  for (int s = 0; s < squarings; ++s) result = result * result;
  return result;
}

}  // namespace matpoint
