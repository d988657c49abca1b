// How tracked particle domains (CPDI2 corners) move in a step: as particles there would under the
// run's velocity transfer and position weight (Nairn 2026 eqs. (7)-(9); cpdi_stencils.hpp).
#pragma once

#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// How CPDI2 corners move in a step (the transfer's position update; see move_domains).
template <int D>
struct DomainMotion {
  double flip = 1.0;   // 1: FLIP, 0: PIC / FMPM, between: blend
  double alpha = 1.0;  // position weight alpha_t of Nairn 2026 eq. (7)
  bool xpic = false;
  const std::vector<Vec<D>>* old_velocity = nullptr;  // V^n of every particle
};

}  // namespace matpoint
