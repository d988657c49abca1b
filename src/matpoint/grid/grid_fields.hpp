// Node fields of the background grid as flat arrays (one entry per node, ghosts included).
#pragma once

#include "matpoint/core/types.hpp"

#include <vector>

namespace matpoint {

template <int D> struct GridFields {
  std::vector<double> mass;
  std::vector<Vec<D>> momentum;      // p = S^T M V               (Nairn 2026 §2.1 task 1)
  std::vector<Vec<D>> force;         // f = -G^T Omega tau + S^T M B   (task 2)
  std::vector<Vec<D>> velocity;      // v(1) = p / m, before the update
  std::vector<Vec<D>> velocity_new;  // v+(1) = (p + f dt) / m, velocity conditions applied (task 3)
  std::vector<Vec<D>> acceleration;  // (v+ - v) / dt, conditions included
  std::vector<Vec<D>> velocity_xpic; // XPIC(k) only: m~_k^-1 p + a dt (Nairn 2026 §1.5 via ref. [1])

  void resize(Index n) {
    mass.assign(n, 0.0);
    momentum.assign(n, Vec<D>::Zero());
    force.assign(n, Vec<D>::Zero());
    velocity.assign(n, Vec<D>::Zero());
    velocity_new.assign(n, Vec<D>::Zero());
    acceleration.assign(n, Vec<D>::Zero());
    velocity_xpic.clear();  // sized by the XPIC transfer when used
  }
};

}  // namespace matpoint
