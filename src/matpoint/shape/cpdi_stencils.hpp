// Convected particle domain interpolation (CPDI; Sadeghirad, Brannon & Burghardt 2011; Gong 2015
// §6.4-6.6; Nairn 2026 §2.1). The particle domain is a segment (1-D), quadrilateral (2-D) or
// hexahedron (3-D) with corners x_c, and the grid function N_i is replaced over the domain by its
// multilinear interpolant from the corners, N_i ~ sum_c N^p_c(x) N_i(x_c) (Gong eq. (6.24)), so
//   S_ip      = (1/V) int N_i  = sum_c w_c N_i(x_c),   w_c = (1/V) int N^p_c dx
//   grad S_ip = (1/V) int grad N_i = sum_c N_i(x_c) g_c,   g_c = (1/V) int grad N^p_c dx.
// w_c and g_c are integrated with 2-point Gauss rules on the isoparametric domain, exact for any
// quadrilateral or hexahedron (N^p_c det J and cof(J) grad_xi N^p_c have degree <= 3 per
// reference coordinate). They equal the closed forms of the papers: for a parallelogram w_c = 1/4
// and g_c of Gong eq. (6.27); for a quadrilateral the CPDI2 coefficients (6Ω ∓ a ∓ b)/(24Ω) of
// §6.5 with the typo "(1 - a - b)" read as 6Ω - a - b, and g_c = (1/2Ω)[y_{c+1} - y_{c-1};
// x_{c-1} - x_{c+1}] (eq. (6.32)); in 1-D w_c = 1/2 and g_c = ∓1/(x_2 - x_1) (§6.6, eqs.
// (6.33)-(6.34) with the 1/(2(x_2 - x_1)) factor of the weight read as 1/2, extraction §5.5).
// Tests: tests/unit/test_shape_family.cpp.
//
// Domains:
//   Parallelogram  CPDI1 and B2CPDI: x_c = x_p + F (±l0), the initial axis-aligned domain of edge
//                  lengths size0 carried by F (r_k = F r_k^0, Gong eq. (6.21)).
//   Tracked        CPDI2: corners stored with the particles and moved by the grid velocity,
//                  x_c += dt sum_i N_i(x_c) v_i (eq. (6.28)); x_p is then the domain centroid
//                  (eq. (6.29), extraction A22).
// Grid functions: HatKernel (CPDI1, CPDI2) or QuadraticKernel (B2CPDI, "CPDI calculated using
// quadratic spline grid functions", Nairn 2026 §3.1). Corners past the grid edge use the folded
// (linearly extrapolated) basis of kernels.hpp, so partition of unity and linear reproduction hold
// and no node outside the arrays is touched.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/particles/particle_set.hpp"
#include "matpoint/shape/domain_motion.hpp"
#include "matpoint/shape/kernels.hpp"

namespace matpoint {

enum class CpdiDomain { Parallelogram, Tracked };

/// Corners of the parallelogram / parallelepiped domain x_p + F (s ⊙ size0 / 2), s in {-1, 1}^D.
template <int D>
typename ParticleSet<D>::Corners parallelogram_corners(const ParticleSet<D>& ps, std::size_t p) {
  typename ParticleSet<D>::Corners c;
  for (int k = 0; k < ParticleSet<D>::kCorners; ++k) {
    Vec<D> s;
    for (int a = 0; a < D; ++a) s[a] = ((k >> a & 1) != 0 ? 0.5 : -0.5) * ps.size0[p][a];
    c[k] = ps.x[p] + ps.F[p] * s;
  }
  return c;
}

/// The reference multilinear functions N_c and their gradients d N_c / d xi at the 2^D Gauss
/// points (±1/sqrt 3)^D of [-1, 1]^D (weights 1), corner c with sign +1 along a where bit a is set.
template <int D>
struct CornerGaussTable {
  static constexpr int C = 1 << D;
  double N[C][C]{};      // [q][c]
  double dN[C][C][D]{};  // [q][c][a]
  constexpr CornerGaussTable() {
    constexpr double gp = 0.57735026918962576451;
    for (int q = 0; q < C; ++q)
      for (int c = 0; c < C; ++c) {
        double f[D]{};
        for (int a = 0; a < D; ++a) {
          const double xi = (q >> a & 1) != 0 ? gp : -gp;
          f[a] = 0.5 * (1.0 + ((c >> a & 1) != 0 ? xi : -xi));
        }
        N[q][c] = 1.0;
        for (int a = 0; a < D; ++a) N[q][c] *= f[a];
        for (int a = 0; a < D; ++a) {
          double d = (c >> a & 1) != 0 ? 0.5 : -0.5;
          for (int b = 0; b < D; ++b)
            if (b != a) d *= f[b];
          dN[q][c][a] = d;
        }
      }
  }
};
template <int D>
inline constexpr CornerGaussTable<D> kCornerGauss{};

/// CPDI corner coefficients w_c, g_c of a domain with corners X (tensor order); returns the
/// domain volume int det J. A degenerate or inverted domain (volume <= 0) gives NaN coefficients,
/// which the step reports as a non-finite particle velocity.
template <int D>
double cpdi_coefficients(const typename ParticleSet<D>::Corners& X, std::array<double, (1 << D)>& w,
                         std::array<Vec<D>, (1 << D)>& g) {
  constexpr int C = 1 << D;
  const auto& table = kCornerGauss<D>;
  double volume = 0.0;
  w.fill(0.0);
  g.fill(Vec<D>::Zero());
  for (int q = 0; q < C; ++q) {
    Mat<D> J = Mat<D>::Zero();
    for (int c = 0; c < C; ++c) J += X[c] * Eigen::Map<const Vec<D>>(table.dN[q][c]).transpose();
    Mat<D> cof;  // det(J) J^{-T}
    if constexpr (D == 1) {
      cof(0, 0) = 1.0;
    } else if constexpr (D == 2) {
      cof << J(1, 1), -J(1, 0), -J(0, 1), J(0, 0);
    } else {
      cof.col(0) = J.col(1).cross(J.col(2));
      cof.col(1) = J.col(2).cross(J.col(0));
      cof.col(2) = J.col(0).cross(J.col(1));
    }
    const double det = J.determinant();
    volume += det;
    for (int c = 0; c < C; ++c) {
      w[c] += table.N[q][c] * det;
      g[c] += cof * Eigen::Map<const Vec<D>>(table.dN[q][c]);
    }
  }
  const double inv = volume > 0.0 ? 1.0 / volume : std::numeric_limits<double>::quiet_NaN();
  for (int c = 0; c < C; ++c) {
    w[c] *= inv;
    g[c] *= inv;
  }
  return volume;
}

/// Per-particle CPDI stencils, evaluated once per step. Each particle's nodes form a box (the union
/// of its corners' grid stencils); the weights and gradients of the box's nodes are stored densely,
/// x fastest, starting at entry offset[p].
template <int D, class Kernel, CpdiDomain Domain>
struct CpdiStencils {
  static constexpr int C = 1 << D;
  static constexpr int W = Kernel::point_width;
  using Corners = typename ParticleSet<D>::Corners;

  std::vector<Index> offset;             // entries of particle p: [offset[p], offset[p + 1])
  std::vector<Index> lowest;             // flat index of the box's lowest node
  std::vector<std::array<int, D>> size;  // box size in nodes per direction
  std::vector<double> weight;
  std::vector<Vec<D>> gradient;
  BrickSchedule<D> bricks;  // the particle order of the particle-to-grid sums
  /// After evaluate(): the lowest storage index of a particle with a domain corner more than one
  /// cell outside the grid (or not finite), -1 if none. The folded basis still gives finite weights
  /// there, but the domain has outgrown the grid: the stepper stops with a numerical failure.
  long first_corner_outside = -1;

  [[nodiscard]] static Corners corners(const ParticleSet<D>& ps, std::size_t p) {
    if constexpr (Domain == CpdiDomain::Tracked)
      return ps.corners[p];
    else
      return parallelogram_corners<D>(ps, p);
  }

  void evaluate(const Grid<D>& grid, const ParticleSet<D>& particles) {
    const auto n = static_cast<std::ptrdiff_t>(particles.size());
    offset.resize(n + 1);
    offset[0] = 0;
    lowest.resize(n);
    size.resize(n);
    // Pass 1: each particle's node box, from the extent of its corners (a corner window's lowest
    // node is monotone in the corner coordinate).
    const Vec<D> low = grid.origin - grid.h, high = grid.domain_max() + grid.h;
    long outside = std::numeric_limits<long>::max();
    int below = 0, above = 0;  // farthest box node below / above a particle's cell, in nodes
    bricks.reset(grid, particles.size());
#pragma omp parallel for schedule(static) reduction(min        \
                                                    : outside) \
    reduction(max                                              \
              : below, above) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      const Corners X = corners(particles, p);
      std::array<int, D> lo;
      Index count = 1;
      for (int a = 0; a < D; ++a) {
        double lo_x = X[0][a], hi_x = X[0][a];
        for (int c = 1; c < C; ++c) {
          lo_x = std::min(lo_x, X[c][a]);
          hi_x = std::max(hi_x, X[c][a]);
        }
        if (!(lo_x >= low[a] && hi_x <= high[a])) outside = std::min(outside, static_cast<long>(p));
        // The same arithmetic as fill() so that both passes find the same windows.
        lo[a] = point_window_start<Kernel>((lo_x - grid.origin[a]) / grid.h[a], grid.cells[a]);
        size[p][a] =
            point_window_start<Kernel>((hi_x - grid.origin[a]) / grid.h[a], grid.cells[a]) + W - lo[a];
        count *= size[p][a];
      }
      lowest[p] = grid.node_index(lo);
      offset[p + 1] = count;
      const auto cell = grid.cell_coords(particles.x[p]);
      for (int a = 0; a < D; ++a) {
        below = std::max(below, cell[a] - lo[a]);
        above = std::max(above, lo[a] + size[p][a] - 1 - cell[a]);
      }
      bricks.assign(p, cell);
    }
    bricks.finish(below, above);
    first_corner_outside = outside == std::numeric_limits<long>::max() ? -1 : outside;
    for (std::ptrdiff_t p = 0; p < n; ++p) offset[p + 1] += offset[p];
    weight.resize(offset[n]);  // fill() writes every entry of its particle
    gradient.resize(offset[n]);
    // Pass 2: corner coefficients and the corners' grid weights, summed into the box.
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) fill(grid, particles, p);
  }

  [[nodiscard]] const BrickSchedule<D>& brick_order() const { return bricks; }

  [[nodiscard]] std::pair<Index, Index> node_span(const Grid<D>& grid, std::size_t p) const {
    Index last = lowest[p];
    for (int a = 0; a < D; ++a) last += (size[p][a] - 1) * grid.stride[a];
    return {lowest[p], last};
  }

  template <class Fn>
  void for_each_node(const Grid<D>& grid, std::size_t p, Fn&& fn) const {
    Index e = offset[p];
    const Index b = lowest[p];
    const auto& n = size[p];
    if constexpr (D == 1) {
      for (int i = 0; i < n[0]; ++i, ++e) fn(b + i, weight[e], gradient[e]);
    } else if constexpr (D == 2) {
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i, ++e) fn(b + i + j * grid.stride[1], weight[e], gradient[e]);
    } else {
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i, ++e)
            fn(b + i + j * grid.stride[1] + k * grid.stride[2], weight[e], gradient[e]);
    }
  }

  /// CPDI2: moves the tracked corners with the grid velocity (Gong eq. (6.28)) and puts the
  /// particle at the centroid of its new domain (eq. (6.29)). Called after the particles moved.
  /// Each corner moves as a particle there would under the run's transfer and position weight
  /// alpha (Nairn 2026 eqs. (7)-(9)): by S (v+ - (1 - alpha) a dt) dt with FLIP, by
  /// (alpha S v+ + (1 - alpha) V^n_p) dt with PIC / FMPM, a blend of the two, or with XPIC by
  /// (S v(1) + (V^{n+1}_p - V^n_p) / 2) dt; the particle-velocity parts are the same for every
  /// corner. (FLIP with alpha = 1 is Gong's eq. (6.28).)
  void move_domains(const Grid<D>& grid, const GridFields<D>& fields, ParticleSet<D>& particles, double dt,
                    const DomainMotion<D>& motion) const requires(Domain == CpdiDomain::Tracked) {
    const auto n = static_cast<std::ptrdiff_t>(particles.size());
    const double flip = motion.flip, alpha = motion.alpha;
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      // The part of the particle's displacement that is the same for every corner (eq. (7)-(9))
      const Vec<D>& v_old = (*motion.old_velocity)[p];
      const Vec<D> uniform =
          motion.xpic ? Vec<D>(0.5 * (particles.v[p] - v_old)) : Vec<D>((1.0 - flip) * (1.0 - alpha) * v_old);
      auto& X = particles.corners[p];
      for (int c = 0; c < C; ++c) {
        std::array<int, D> i0;
        double w[D][W], dw[W];
        for (int a = 0; a < D; ++a)
          i0[a] = point_on_grid<Kernel>((X[c][a] - grid.origin[a]) / grid.h[a], grid.cells[a], w[a], dw);
        const Index b = grid.node_index(i0);
        Vec<D> v = Vec<D>::Zero();
        for_each_tensor_node(grid, b, w, [&](Index node, double N) {
          if (motion.xpic) {
            v += N * fields.velocity[node];
          } else {
            const Vec<D>& v_plus = fields.velocity_new[node];
            v += N * (flip * (v_plus - (1.0 - alpha) * dt * fields.acceleration[node]) +
                      (1.0 - flip) * alpha * v_plus);
          }
        });
        X[c] += dt * (v + uniform);
      }
      std::array<double, C> wc;
      std::array<Vec<D>, C> gc;
      cpdi_coefficients<D>(X, wc, gc);
      Vec<D> centroid = Vec<D>::Zero();
      for (int c = 0; c < C; ++c) centroid += wc[c] * X[c];
      particles.x[p] = centroid;
    }
  }

 private:
  /// fn(node, N) over the W^D nodes of a tensor stencil with 1-D weights w[a][k] from node b.
  template <class Fn>
  static void for_each_tensor_node(const Grid<D>& grid, Index b, const double (*w)[W], Fn&& fn) {
    if constexpr (D == 1) {
      for (int i = 0; i < W; ++i) fn(b + i, w[0][i]);
    } else if constexpr (D == 2) {
      for (int j = 0; j < W; ++j)
        for (int i = 0; i < W; ++i) fn(b + i + j * grid.stride[1], w[0][i] * w[1][j]);
    } else {
      for (int k = 0; k < W; ++k)
        for (int j = 0; j < W; ++j)
          for (int i = 0; i < W; ++i)
            fn(b + i + j * grid.stride[1] + k * grid.stride[2], w[0][i] * w[1][j] * w[2][k]);
    }
  }

  /// w_c, g_c of particle p. A parallelogram / parallelepiped x_p + J xi with constant
  /// J = F diag(size0 / 2) has w_c = 1 / 2^D and g_c = J^{-T} s_c / 2^D (s_c the corner's signs;
  /// Gong eqs. (6.26)-(6.27)); a tracked domain is integrated by cpdi_coefficients.
  static void coefficients(const ParticleSet<D>& ps, std::size_t p, const Corners& X,
                           std::array<double, C>& w, std::array<Vec<D>, C>& g) {
    if constexpr (Domain == CpdiDomain::Tracked) {
      cpdi_coefficients<D>(X, w, g);
    } else {
      const Mat<D> J = ps.F[p] * (0.5 * ps.size0[p]).asDiagonal();
      const double det = J.determinant();
      const Mat<D> inv_t = det > 0.0 ? Mat<D>(J.inverse().transpose())
                                     : Mat<D>::Constant(std::numeric_limits<double>::quiet_NaN());
      for (int c = 0; c < C; ++c) {
        Vec<D> s;
        for (int a = 0; a < D; ++a) s[a] = (c >> a & 1) != 0 ? 1.0 : -1.0;
        w[c] = 1.0 / C;
        g[c] = inv_t * s / C;
      }
    }
  }

  void fill(const Grid<D>& grid, const ParticleSet<D>& particles, std::size_t p) {
    const Corners X = corners(particles, p);
    std::array<double, C> wc;
    std::array<Vec<D>, C> gc;
    coefficients(particles, p, X, wc, gc);
    int i0[C][D];
    double w[C][D][W], dw[W];
    std::array<int, D> lo;
    lo.fill(std::numeric_limits<int>::max());
    for (int c = 0; c < C; ++c)
      for (int a = 0; a < D; ++a) {
        i0[c][a] = point_on_grid<Kernel>((X[c][a] - grid.origin[a]) / grid.h[a], grid.cells[a], w[c][a], dw);
        lo[a] = std::min(lo[a], i0[c][a]);
      }
    const auto& n = size[p];
    const Index e0 = offset[p], e1 = offset[p + 1];
    std::fill(weight.begin() + e0, weight.begin() + e1, 0.0);
    std::fill(gradient.begin() + e0, gradient.begin() + e1, Vec<D>::Zero());
    const Index sy = D >= 2 ? n[0] : 0, sz = D == 3 ? static_cast<Index>(n[0]) * n[1] : 0;
    for (int c = 0; c < C; ++c) {
      // Local box index of the corner stencil's first node, then its W^D nodes.
      Index first = i0[c][0] - lo[0];
      // cppcheck-suppress containerOutOfBounds ; if constexpr: only compiled for D >= 2
      if constexpr (D >= 2) first += (i0[c][1] - lo[1]) * sy;
      // cppcheck-suppress containerOutOfBounds ; if constexpr: only compiled for D == 3
      if constexpr (D == 3) first += (i0[c][2] - lo[2]) * sz;
      auto add = [&](Index local, double N) {
        weight[e0 + local] += wc[c] * N;
        gradient[e0 + local] += N * gc[c];
      };
      const auto& wa = w[c];
      if constexpr (D == 1) {
        for (int i = 0; i < W; ++i) add(first + i, wa[0][i]);
      } else if constexpr (D == 2) {
        for (int j = 0; j < W; ++j)
          for (int i = 0; i < W; ++i) add(first + i + j * sy, wa[0][i] * wa[1][j]);
      } else {
        for (int k = 0; k < W; ++k)
          for (int j = 0; j < W; ++j)
            for (int i = 0; i < W; ++i) add(first + i + j * sy + k * sz, wa[0][i] * wa[1][j] * wa[2][k]);
      }
    }
  }
};

}  // namespace matpoint
