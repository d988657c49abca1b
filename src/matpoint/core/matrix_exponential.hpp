// exp(A) for small fixed-size matrices: scaling and squaring with a Taylor polynomial.
#pragma once

#include "matpoint/core/types.hpp"

#include <cmath>

namespace matpoint {

/// Scales A until its norm is below 1/4, sums the Taylor series until the next term is below
/// 1e-17 (at most order 12: (1/4)^13 / 13! < 1e-17), then squares back. Exact to round-off; for
/// the velocity-gradient increments of MPM (|L dt| ~ 1e-3) about five terms suffice.
template <int D> Mat<D> matrix_exponential(const Mat<D>& A) {
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();  // infinity norm
  int squarings = 0;
  if (norm > 0.25) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.25)));
  const Mat<D> B = A / std::ldexp(1.0, squarings);
  Mat<D> term = Mat<D>::Identity();
  Mat<D> sum = Mat<D>::Identity();
  const double scaled_norm = norm / std::ldexp(1.0, squarings);
  double term_bound = 1.0;  // bound of |B^k / k!| in the infinity norm
  for (int k = 1; k <= 12 && term_bound > 1e-17; ++k) {
    term = term * B / k;
    sum += term;
    term_bound *= scaled_norm / (k + 1);
  }
  for (int s = 0; s < squarings; ++s) sum = sum * sum;
  return sum;
}

}  // namespace matpoint
