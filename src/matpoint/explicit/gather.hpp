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
  /// Nodes at or below this mass are inactive (solver.mass_tolerance times the heaviest particle;
  /// 0 by default: every node a particle reaches is active). Where it is positive, the particle
  /// sees only its active nodes, through the renormalised shape functions S_i / sum_active S_j
  /// (Shepard), so that an inactive node enters neither the velocity nor the velocity gradient.
  double mass_floor = 0.0;
};

/// Sums over the active nodes of one particle's stencil for the renormalisation above: with
/// S = sum S_i and dS = sum grad S_i over active nodes, the renormalised functions are
/// S~_i = S_i / S and grad S~_i = grad S_i / S - S_i dS / S^2, so a field f interpolates as
/// f_p = (sum S_i f_i) / S and its gradient as (sum f_i (x) grad S_i) / S - f_p (x) dS / S.
template <int D>
struct ActiveNodeSums {
  double weight = 0.0;
  Vec<D> gradient = Vec<D>::Zero();
  void add(double N, const Vec<D>& dN) {
    weight += N;
    gradient += dN;
  }
  /// Renormalises a value and the gradient gathered with the raw functions (value first).
  void renormalise(Vec<D>& value, Mat<D>* gradient_of_value) const {
    if (!(weight > 0.0)) return;
    value /= weight;
    if (gradient_of_value) *gradient_of_value = (*gradient_of_value - value * gradient.transpose()) / weight;
  }
};

struct GatherResult {
  double gravity_work = 0.0;  // sum_p M_p b . (X^{n+1} - X^n)
  long first_outside = -1;    // smallest index of a particle that left the domain, or -1
  long first_too_fast = -1;   // smallest index of a particle that moved more than a cell, or -1
};

namespace detail {

/// The particle update of one transfer; Xpic selects the XPIC(k) form, else FLIP/PIC/blend.
/// Renormalise: skip nodes at or below mass_floor and renormalise (ActiveNodeSums).
template <bool Xpic, bool Renormalise, int D, class Stencils>
GatherResult gather_and_move(const Grid<D>& grid, const Stencils& stencils, const GridFields<D>& fields,
                             ParticleSet<D>& particles, double flip, double alpha, double mass_floor,
                             double dt, bool with_gradient, const Vec<D>& gravity) {
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
    ActiveNodeSums<D> active;
    [[maybe_unused]] const auto inactive = [&](Index node, double N, const Vec<D>& dN) {
      if constexpr (Renormalise) {
        if (!(fields.mass[node] > mass_floor)) return true;
        active.add(N, dN);
      }
      return false;
    };
    if constexpr (Xpic) {  // V = S (m~_k^-1 p + a dt),  X += (S v(1) + (V^{n+1} - V^n) / 2) dt
      Vec<D> v_lumped = Vec<D>::Zero(), v_plus = Vec<D>::Zero();
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        if (inactive(node, N, dN)) return;
        v_new += N * fields.velocity_xpic[node];
        v_lumped += N * fields.velocity[node];
        if (with_gradient) {
          L += fields.velocity_new[node] * dN.transpose();
          if constexpr (Renormalise) v_plus += N * fields.velocity_new[node];
        }
      });
      if constexpr (Renormalise) {
        active.renormalise(v_new, nullptr);
        active.renormalise(v_lumped, nullptr);
        active.renormalise(v_plus, with_gradient ? &L : nullptr);
      }
      dx = (v_lumped + 0.5 * (v_new - v_old)) * dt;
      particles.v[p] = v_new;
    } else {
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        if (inactive(node, N, dN)) return;
        v_new += N * fields.velocity_new[node];
        a += N * fields.acceleration[node];
        if (with_gradient) L += fields.velocity_new[node] * dN.transpose();
      });
      if constexpr (Renormalise) {
        active.renormalise(v_new, with_gradient ? &L : nullptr);
        active.renormalise(a, nullptr);
      }
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
  const double floor = transfer.mass_floor;
  if (transfer.kind == VelocityTransfer::XPIC)
    return floor > 0.0 ? detail::gather_and_move<true, true>(grid, stencils, fields, particles, 0.0, 0.5, floor, dt,
                                                             with_gradient, gravity)
                       : detail::gather_and_move<true, false>(grid, stencils, fields, particles, 0.0, 0.5, floor,
                                                              dt, with_gradient, gravity);
  const double flip = transfer.kind == VelocityTransfer::FLIP    ? 1.0
                      : transfer.kind == VelocityTransfer::Blend ? transfer.flip_fraction
                                                                 : 0.0;  // PIC, FMPM
  return floor > 0.0 ? detail::gather_and_move<false, true>(grid, stencils, fields, particles, flip,
                                                            transfer.alpha, floor, dt, with_gradient, gravity)
                     : detail::gather_and_move<false, false>(grid, stencils, fields, particles, flip,
                                                             transfer.alpha, floor, dt, with_gradient, gravity);
}

/// L_p = sum_i v_i (x) grad S_pi for a given node velocity field (USF, MUSL). With a positive
/// mass_floor, over the active nodes with the renormalised functions (TransferParameters).
template <int D, class Stencils>
void gather_velocity_gradient(const Grid<D>& grid, const Stencils& stencils, const std::vector<Vec<D>>& velocity,
                              ParticleSet<D>& particles, const std::vector<double>& mass, double mass_floor) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  if (mass_floor > 0.0) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      Mat<D> L = Mat<D>::Zero();
      Vec<D> v = Vec<D>::Zero();
      ActiveNodeSums<D> active;
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        if (!(mass[node] > mass_floor)) return;
        active.add(N, dN);
        v += N * velocity[node];
        L += velocity[node] * dN.transpose();
      });
      active.renormalise(v, &L);
      particles.L[p] = L;
    }
    return;
  }
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t p = 0; p < n; ++p) {
    Mat<D> L = Mat<D>::Zero();
    stencils.for_each_node(
        grid, p, [&](Index node, double, const Vec<D>& dN) { L += velocity[node] * dN.transpose(); });
    particles.L[p] = L;
  }
}

}  // namespace matpoint
