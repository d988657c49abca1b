// Removing particles from a set: every per-particle array (for_each_array) keeps the survivors in
// their order. Used by the meshfree method's deletion of points without shape functions
// (Iaconeta et al. 2017 §6.5 as the authors' code does it; implicit/meshfree/meshfree_solver.hpp).
#pragma once

#include <cstddef>
#include <vector>

#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// Keeps the entries of `values` (stride values per item) whose item `gone` does not flag, in order.
template <class Values>
void keep_unflagged(Values& values, const std::vector<char>& gone, std::size_t stride) {
  if (values.empty() || stride == 0) return;
  std::size_t to = 0;
  for (std::size_t p = 0; p < gone.size(); ++p)
    if (!gone[p]) {
      for (std::size_t k = 0; k < stride; ++k) values[to * stride + k] = values[p * stride + k];
      ++to;
    }
  values.resize(to * stride);
}

/// Drops the particles that `gone` flags (one flag per particle, storage order). Their ids are not
/// reused: the survivors keep theirs, so ids are no longer 0 .. n - 1 (io/checkpoint.cpp allows it).
template <int D>
void remove_particles(ParticleSet<D>& ps, const std::vector<char>& gone) {
  for_each_array(
      ps, [&](const char*, auto& values, std::size_t stride) { keep_unflagged(values, gone, stride); });
  ps.recorded_wave_speed = -1.0;  // the set of particles changed (particle_set.hpp)
}

}  // namespace matpoint
