// Particle-to-grid transfers (Nairn 2026 §2.1 tasks 1 and 2): nodal mass, momentum and force.
//   m_i = sum_p M_p S_pi,  p_i = sum_p M_p S_pi V_p,
//   f_i = -sum_p V_p sigma_p grad S_pi + sum_p M_p S_pi b          (V_p sigma_p = V0_p tau_p)
// b is the uniform gravity plus, when given, a per-particle body force b_p (per unit mass), e.g. a
// manufactured solution's B(X_p, t) (Gong 2015 eqs. (4.17), (4.39)).
// Race-free with threads: each thread scatters its contiguous block of (cell-sorted) particles
// into a private band of nodes, and the bands are summed node by node in thread order, so a
// given thread count always gives the same result.
#pragma once

#include <algorithm>
#include <vector>

#include "matpoint/explicit/particle_blocks.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

enum ScatterFields : unsigned { kScatterMass = 1, kScatterMomentum = 2, kScatterForce = 4 };

/// Per-thread node bands reused from step to step.
template <int D>
struct ScatterWorkspace {
  struct Band {
    Index lo = 0, hi = -1;
    std::vector<double> mass;
    std::vector<Vec<D>> momentum, force;
  };
  std::vector<Band> bands;
};

namespace detail {

template <int D, unsigned What, class Stencils, class Target>
void scatter_range(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                   const std::vector<Vec<D>>& velocity, const Vec<D>& gravity,
                   const std::vector<Vec<D>>* body, std::ptrdiff_t begin, std::ptrdiff_t end, Index offset,
                   Target& out) {
  for (std::ptrdiff_t p = begin; p < end; ++p) {
    const double m = particles.mass[p];
    Vec<D> mv = Vec<D>::Zero();
    if constexpr ((What & kScatterMomentum) != 0) mv = m * velocity[p];
    Mat<D> vs = Mat<D>::Zero();
    Vec<D> mb = Vec<D>::Zero();
    if constexpr ((What & kScatterForce) != 0) {
      vs = particles.volume0[p] * particles.F[p].determinant() * particles.stress[p];
      mb = body != nullptr ? Vec<D>(m * (gravity + (*body)[p])) : Vec<D>(m * gravity);
    }
    stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
      const Index k = node - offset;
      if constexpr ((What & kScatterMass) != 0) out.mass[k] += m * N;
      if constexpr ((What & kScatterMomentum) != 0) out.momentum[k] += N * mv;
      if constexpr ((What & kScatterForce) != 0) out.force[k] += N * mb - vs * dN;
    });
  }
}

template <int D, unsigned What>
void zero_fields(GridFields<D>& f, Index lo, Index hi) {
  for (Index i = lo; i <= hi; ++i) {
    if constexpr ((What & kScatterMass) != 0) f.mass[i] = 0.0;
    if constexpr ((What & kScatterMomentum) != 0) f.momentum[i].setZero();
    if constexpr ((What & kScatterForce) != 0) f.force[i].setZero();
  }
}

}  // namespace detail

/// Recomputes the selected node fields from the particles (the fields not selected are untouched).
/// The momentum is sum_p M_p S_pi U_p with U = `velocity` when given (the FMPM passes), else V_p.
/// `body` (optional, by particle storage index) adds a per-particle body force to the gravity.
template <unsigned What, int D, class Stencils>
void scatter_to_grid(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                     const Vec<D>& gravity, GridFields<D>& fields, ScatterWorkspace<D>& ws,
                     const std::vector<Vec<D>>* velocity = nullptr,
                     const std::vector<Vec<D>>* body = nullptr) {
  const auto& u = velocity != nullptr ? *velocity : particles.v;
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const int threads = scatter_threads(n);
  if (threads == 1) {
    detail::zero_fields<D, What>(fields, 0, grid.node_count - 1);
    detail::scatter_range<D, What>(grid, stencils, particles, u, gravity, body, 0, n, 0, fields);
    return;
  }
  ws.bands.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    const int t = thread_number();
    const ParticleBlock block = particle_block(grid, stencils, n, t, threads);
    auto& band = ws.bands[t];
    band.lo = block.lo, band.hi = block.hi;
    const Index width = block.width();
    if constexpr ((What & kScatterMass) != 0) band.mass.assign(width, 0.0);
    if constexpr ((What & kScatterMomentum) != 0) band.momentum.assign(width, Vec<D>::Zero());
    if constexpr ((What & kScatterForce) != 0) band.force.assign(width, Vec<D>::Zero());
    detail::scatter_range<D, What>(grid, stencils, particles, u, gravity, body, block.begin, block.end,
                                   band.lo, band);
#pragma omp barrier
#pragma omp for schedule(static)
    for (Index i = 0; i < grid.node_count; ++i) {
      double m = 0.0;
      Vec<D> mv = Vec<D>::Zero(), f = Vec<D>::Zero();
      for (const auto& b : ws.bands) {
        if (i < b.lo || i > b.hi) continue;
        if constexpr ((What & kScatterMass) != 0) m += b.mass[i - b.lo];
        if constexpr ((What & kScatterMomentum) != 0) mv += b.momentum[i - b.lo];
        if constexpr ((What & kScatterForce) != 0) f += b.force[i - b.lo];
      }
      if constexpr ((What & kScatterMass) != 0) fields.mass[i] = m;
      if constexpr ((What & kScatterMomentum) != 0) fields.momentum[i] = mv;
      if constexpr ((What & kScatterForce) != 0) fields.force[i] = f;
    }
  }
}

}  // namespace matpoint
