// The deformation gradient's update over one step (Nairn 2026 §2.1 task 5): F <- dF F with
// dF = exp(L dt) (exact for a constant velocity gradient) or dF = I + L dt (first order).
#pragma once

#include "matpoint/core/matrix_exponential.hpp"
#include "matpoint/core/types.hpp"

namespace matpoint {

template <int D>
[[nodiscard]] inline Mat<D> advanced_deformation(const Mat<D>& F, const Mat<D>& L, double dt,
                                                 bool exponential) {
  if (exponential) return matrix_exponential<D>(L * dt) * F;
  return (Mat<D>::Identity() + L * dt) * F;
}

}  // namespace matpoint
