// The deformation gradient's exponential update F <- exp(L dt) F (deformation_increment.hpp) for
// kLanes particles at once: the Taylor branch of matrix_exponential.hpp with each lane's own
// degree, the same operations per lane, so bitwise the scalar result (core/lanes.hpp).
#pragma once

#include "matpoint/core/lanes.hpp"
#include "matpoint/core/matrix_exponential.hpp"

namespace matpoint {

/// exp(A) per lane, as matrix_exponential_detail::taylor: true when every lane's infinity norm is
/// at most 1/4 (matrix_exponential's Taylor branch); false otherwise (a lane needing scaling and
/// squaring, or not finite), and then the caller takes the scalar path for these particles.
/// Each lane adds the terms up to its own degree (the smallest m with norm <= kTaylorNormLimit[m-1]);
/// the powers are formed up to the batch's highest degree, and a lane past its degree keeps its sum.
template <int D>
[[nodiscard]] bool taylor_exponential_lanes(const LaneMatrix<D>& A, LaneMatrix<D>& result) {
  using namespace matrix_exponential_detail;
  const Lanes norm = A.infinity_norm();
  if (!stdx::all_of(norm <= kScalingThreshold)) return false;  // also false for a NaN
  Lanes degree(1.0);  // the limits grow with m, and 1/4 < kTaylorNormLimit[11]: m <= 12
  int highest = 1;
  for (int m = 1; m < 12; ++m) {
    const LaneMask above = norm > kTaylorNormLimit[static_cast<std::size_t>(m - 1)];
    if (stdx::none_of(above)) break;
    stdx::where(above, degree) = static_cast<double>(m + 1);
    highest = m + 1;
  }
  auto has_term = [&](int k) { return LaneMask(degree >= static_cast<double>(k)); };
  result = A;
  for (int i = 0; i < D; ++i) result(i, i) += 1.0;
  if (highest == 1) return true;
  const LaneMatrix<D> A2 = A * A;
  result.add_where(has_term(2), A2 * Lanes(0.5));
  LaneMatrix<D> even = A2, odd = A2 * A;  // A^k for the next even and odd k, as taylor<D>
  for (int k = 3; k <= highest; k += 2) {
    result.add_where(has_term(k), odd * Lanes(kInverseFactorial[static_cast<std::size_t>(k)]));
    if (k + 1 > highest) break;
    even = even * A2;
    result.add_where(has_term(k + 1), even * Lanes(kInverseFactorial[static_cast<std::size_t>(k + 1)]));
    if (k + 2 <= highest) odd = odd * A2;
  }
  return true;
}

/// F <- exp(L dt) F for the kLanes particles from `first`: false (nothing written) when a lane's
/// |L dt| needs the scalar path (see taylor_exponential_lanes).
template <int D>
[[nodiscard]] bool advance_deformation_lanes(Mat<D>* F_first, const Mat<D>* L_first, double dt) {
  LaneMatrix<D> increment;
  if (!taylor_exponential_lanes<D>(LaneMatrix<D>::load(L_first) * Lanes(dt), increment)) return false;
  (increment * LaneMatrix<D>::load(F_first)).store(F_first);
  return true;
}

}  // namespace matpoint
