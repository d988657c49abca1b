// exp(A) for small fixed-size matrices: scaling and squaring with a Taylor polynomial.
#pragma once

#include "matpoint/core/types.hpp"

#include <cmath>

namespace matpoint {

/// Scales A until its norm is below 1/4, sums the Taylor series to order 10 (truncation error
/// below (1/4)^11 / 11! ~ 6e-15 relative), then squares back. Exact to round-off for the
/// velocity-gradient increments of MPM, where |L dt| is usually far below 1.
template <int D> Mat<D> matrix_exponential(const Mat<D>& A) {
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();  // infinity norm
  int squarings = 0;
  if (norm > 0.25) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.25)));
  const Mat<D> B = A / std::ldexp(1.0, squarings);
  Mat<D> term = Mat<D>::Identity();
  Mat<D> sum = Mat<D>::Identity();
  for (int k = 1; k <= 10; ++k) {
    term = term * B / k;
    sum += term;
  }
  for (int s = 0; s < squarings; ++s) sum = sum * sum;
  return sum;
}

}  // namespace matpoint
