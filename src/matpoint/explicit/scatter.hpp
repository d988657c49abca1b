// Particle-to-grid transfers (Nairn 2026 §2.1 tasks 1 and 2): nodal mass, momentum and force.
//   m_i = sum_p M_p S_pi,  p_i = sum_p M_p S_pi V_p,
//   f_i = -sum_p V_p sigma_p grad S_pi + sum_p M_p S_pi b          (V_p sigma_p = V0_p tau_p)
// b is the uniform gravity plus, when given, a per-particle body force b_p (per unit mass), e.g. a
// manufactured solution's B(X_p, t) (Gong 2015 eqs. (4.17), (4.39)).
// Race-free with threads and independent of their number: the particles are visited in the
// stencils' brick order (grid/brick_schedule.hpp), so every node sums its terms in one fixed order.
#pragma once

#include <span>
#include <vector>

#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

enum ScatterFields : unsigned { kScatterMass = 1, kScatterMomentum = 2, kScatterForce = 4 };

/// Recomputes the selected node fields from the particles (the fields not selected are untouched).
/// The momentum is sum_p M_p S_pi U_p with U = `velocity` when given (the FMPM passes), else V_p.
/// `body` (optional, by particle storage index) adds a per-particle body force to the gravity.
template <unsigned What, int D, class Stencils>
void scatter_to_grid(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                     const Vec<D>& gravity, GridFields<D>& fields,
                     const std::vector<Vec<D>>* velocity = nullptr,
                     const std::vector<Vec<D>>* body = nullptr) {
  const auto& u = velocity != nullptr ? *velocity : particles.v;
  const Index nodes = grid.node_count;  // of every field in a multi-field run (its field grid)
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
  for (Index i = 0; i < nodes; ++i) {
    if constexpr ((What & kScatterMass) != 0) fields.mass[i] = 0.0;
    if constexpr ((What & kScatterMomentum) != 0) fields.momentum[i].setZero();
    if constexpr ((What & kScatterForce) != 0) fields.force[i].setZero();
  }
  double* const mass = fields.mass.data();  // raw pointers: no reloads through `fields` per node
  Vec<D>* const momentum = fields.momentum.data();
  Vec<D>* const force = fields.force.data();
  // The arrays this sum writes, for a decomposed run's hand-off between colours (momentum and
  // force are D contiguous doubles per node).
  NodeArray written[3];
  int count = 0;
  if constexpr ((What & kScatterMass) != 0) written[count++] = {mass, 1, nodes};
  if constexpr ((What & kScatterMomentum) != 0) written[count++] = {momentum->data(), D, nodes};
  if constexpr ((What & kScatterForce) != 0) written[count++] = {force->data(), D, nodes};
  static_assert(sizeof(Vec<D>) == D * sizeof(double));
  const auto add_particle = [&](std::size_t p) {
    const double m = particles.mass[p];
    Vec<D> mv = Vec<D>::Zero();
    if constexpr ((What & kScatterMomentum) != 0) mv = m * u[p];
    Mat<D> vs = Mat<D>::Zero();
    Vec<D> mb = Vec<D>::Zero();
    if constexpr ((What & kScatterForce) != 0) {
      vs = particles.volume0[p] * particles.F[p].determinant() * particles.stress[p];
      mb = body != nullptr ? Vec<D>(m * (gravity + (*body)[p])) : Vec<D>(m * gravity);
    }
    stencils.for_each_node(grid, p, [&](Index k, double N, const Vec<D>& dN) {
      if constexpr ((What & kScatterMass) != 0) mass[k] += m * N;
      if constexpr ((What & kScatterMomentum) != 0) momentum[k] += N * mv;
      if constexpr ((What & kScatterForce) != 0) force[k] += N * mb - vs * dN;
    });
  };
  stencils.brick_order().for_each_particle(
      add_particle, std::span<const NodeArray>(written, static_cast<std::size_t>(count)));
}

}  // namespace matpoint
