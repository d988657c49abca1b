// Grid-to-particle transfers (Nairn 2026 §2.1 task 4 and eqs. (7)-(8)) and the velocity gradient
// of task 5, L_p = sum_i v_i (x) grad S_pi.
#pragma once

#include <algorithm>
#include <limits>

#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

struct TransferParameters {
  VelocityTransfer kind = VelocityTransfer::FLIP;
  double alpha = 1.0;          // position weight alpha_t of eq. (7)
  double flip_fraction = 1.0;  // Blend only
};

struct GatherResult {
  double gravity_work = 0.0;  // sum_p M_p b . (X^{n+1} - X^n)
  long first_outside = -1;    // smallest index of a particle that left the domain, or -1
  long first_too_fast = -1;   // smallest index of a particle that moved more than a cell, or -1
};

namespace detail {

/// The particle update of one transfer; Xpic selects the XPIC(k) form, else FLIP/PIC/blend.
template <bool Xpic, int D, class Stencils>
GatherResult gather_and_move(const Grid<D>& grid, const Stencils& stencils, const GridFields<D>& fields,
                             ParticleSet<D>& particles, double flip, double alpha, double dt,
                             bool with_gradient, const Vec<D>& gravity) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  double work = 0.0;
  long outside = std::numeric_limits<long>::max(), too_fast = outside;
  Vec<D> inv_h;
  for (int a = 0; a < D; ++a) inv_h[a] = 1.0 / grid.h[a];
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(+ : work) \
    reduction(min : outside, too_fast)
  for (std::ptrdiff_t p = 0; p < n; ++p) {
    Vec<D> v_new = Vec<D>::Zero(), a = Vec<D>::Zero();
    Mat<D> L = Mat<D>::Zero();
    const Vec<D> v_old = particles.v[p];
    Vec<D> dx;
    if constexpr (Xpic) {  // V = S (m~_k^-1 p + a dt),  X += (S v(1) + (V^{n+1} - V^n) / 2) dt
      Vec<D> v_lumped = Vec<D>::Zero();
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        v_new += N * fields.velocity_xpic[node];
        v_lumped += N * fields.velocity[node];
        if (with_gradient) L += fields.velocity_new[node] * dN.transpose();
      });
      dx = (v_lumped + 0.5 * (v_new - v_old)) * dt;
      particles.v[p] = v_new;
    } else {
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        v_new += N * fields.velocity_new[node];
        a += N * fields.acceleration[node];
        if (with_gradient) L += fields.velocity_new[node] * dN.transpose();
      });
      const Vec<D> v_flip = v_old + a * dt;
      const Vec<D> dx_flip = (v_new - (1.0 - alpha) * a * dt) * dt;
      const Vec<D> dx_pic = (alpha * v_new + (1.0 - alpha) * v_old) * dt;
      dx = flip * dx_flip + (1.0 - flip) * dx_pic;
      particles.v[p] = flip * v_flip + (1.0 - flip) * v_new;
    }
    particles.x[p] += dx;
    if (with_gradient) particles.L[p] = L;
    work += particles.mass[p] * gravity.dot(dx);
    if (!grid.contains(particles.x[p]) || !particles.v[p].allFinite())
      outside = std::min(outside, static_cast<long>(p));
    // A particle that crosses more than a cell in one step has outrun its stencil: the particle
    // Courant number |dx| / h exceeds 1 and the step is no longer consistent.
    if ((dx.cwiseAbs().cwiseProduct(inv_h)).maxCoeff() > 1.0) too_fast = std::min(too_fast, static_cast<long>(p));
  }
  constexpr long none = std::numeric_limits<long>::max();
  return {work, outside == none ? -1 : outside, too_fast == none ? -1 : too_fast};
}

}  // namespace detail

/// Updates particle velocities and positions from v+ (velocity_new) and a = (v+ - v)/dt:
///   FLIP   V += S a dt,          X += (S v+ - (1 - alpha) S a dt) dt           eq. (8)
///   PIC    V  = S v+,            X += (alpha V^{n+1} + (1 - alpha) V^n) dt     eq. (9) with k = 1
///   FMPM   as PIC, with v+ = v+(k) from the FMPM loop                          eq. (9)
///   Blend  f FLIP + (1 - f) PIC for both.
///   XPIC   V = S (m~_k^-1 p + a dt), X += (S v(1) + (V^{n+1} - V^n)/2) dt      (§1.5, ref. [1])
/// With `with_gradient` it also stores L_p from v+ (USL: the same grid velocity moves the particles
/// and strains them).
template <int D, class Stencils>
GatherResult gather_and_move(const Grid<D>& grid, const Stencils& stencils, const GridFields<D>& fields,
                             ParticleSet<D>& particles, const TransferParameters& transfer, double dt,
                             bool with_gradient, const Vec<D>& gravity) {
  if (transfer.kind == VelocityTransfer::XPIC)
    return detail::gather_and_move<true>(grid, stencils, fields, particles, 0.0, 0.5, dt, with_gradient,
                                         gravity);
  const double flip = transfer.kind == VelocityTransfer::FLIP    ? 1.0
                      : transfer.kind == VelocityTransfer::Blend ? transfer.flip_fraction
                                                                 : 0.0;  // PIC, FMPM
  return detail::gather_and_move<false>(grid, stencils, fields, particles, flip, transfer.alpha, dt,
                                        with_gradient, gravity);
}

/// L_p = sum_i v_i (x) grad S_pi for a given node velocity field (USF, MUSL).
template <int D, class Stencils>
void gather_velocity_gradient(const Grid<D>& grid, const Stencils& stencils,
                              const std::vector<Vec<D>>& velocity, ParticleSet<D>& particles) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t p = 0; p < n; ++p) {
    Mat<D> L = Mat<D>::Zero();
    stencils.for_each_node(
        grid, p, [&](Index node, double, const Vec<D>& dN) { L += velocity[node] * dN.transpose(); });
    particles.L[p] = L;
  }
}

}  // namespace matpoint
