// One-dimensional node-centred kernels on the unbounded unit lattice, and the fold that keeps every
// stencil inside the grid. Coordinates are in cells: a kernel K is centred on node j and evaluated
// at r = xi - j. Each kernel gives
//   value(r)    = K(r)
//   integral(r) = int_{-inf}^{r} K(s) ds        (for the particle-domain averages of GIMP)
//   point(xi)   = the lowest node and the `point_width` weights K(xi - j) and slopes dK/dxi.
// The kernels are the linear hat and the uniform quadratic and cubic B-splines; all three are a
// partition of unity and reproduce linear functions on the unbounded lattice.
//
// Grid edge (fold_to_grid): the nodes j < 0 and j > cells do not exist. Their weights are folded
// onto the two edge nodes as if the nodal values there were the linear extrapolation of the edge
// values, u_j = (1 - j) u_0 + j u_1 (j < 0) and u_j = (1 + j - c) u_c - (j - c) u_{c-1} (j > c).
// Because the fold is exact for linear nodal data, it keeps partition of unity, linear
// reproduction and the zero sum of gradients, for points and particle domains anywhere (also
// outside the grid), and the stencil never reads outside the node arrays. For the quadratic
// B-spline and a point inside the grid this is the boundary-modified kernel already used by
// QuadraticBSplineBasis (tensor_bases.hpp); for the cubic B-spline it is the open (clamped) knot
// vector basis, see CubicKernel.
#pragma once

#include <algorithm>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// Linear hat, support [-1, 1].
struct HatKernel {
  static constexpr int point_width = 2;
  static constexpr double radius = 1.0;

  static double value(double r) {
    const double a = std::abs(r);
    return a < 1.0 ? 1.0 - a : 0.0;
  }
  static double integral(double r) {
    if (r <= -1.0) return 0.0;
    if (r <= 0.0) return 0.5 * (1.0 + r) * (1.0 + r);
    if (r <= 1.0) return 1.0 - 0.5 * (1.0 - r) * (1.0 - r);
    return 1.0;
  }
  static int first_node(double xi) { return floor_to_int(xi); }
  /// Weights and slopes of the two nodes of a cell at the local coordinate r in [0, 1].
  static void cell_weights(double r, double* w, double* dw) {
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
  static int point(double xi, double* w, double* dw) {
    const int i0 = first_node(xi);
    cell_weights(xi - i0, w, dw);
    return i0;
  }
};

/// Uniform quadratic B-spline, support [-3/2, 3/2] (Gong 2015 eq. (5.2); Steffen et al. 2008).
struct QuadraticKernel {
  static constexpr int point_width = 3;
  static constexpr double radius = 1.5;

  static double value(double r) {
    const double a = std::abs(r);
    if (a < 0.5) return 0.75 - a * a;
    if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
    return 0.0;
  }
  static double integral(double r) {
    if (r <= -1.5) return 0.0;
    if (r <= -0.5) return (r + 1.5) * (r + 1.5) * (r + 1.5) / 6.0;
    if (r <= 0.5) return 1.0 / 6.0 + 0.75 * (r + 0.5) - (r * r * r + 0.125) / 3.0;
    if (r <= 1.5) return 1.0 - (1.5 - r) * (1.5 - r) * (1.5 - r) / 6.0;
    return 1.0;
  }
  static int first_node(double xi) { return floor_to_int(xi + 0.5) - 1; }
  static int point(double xi, double* w, double* dw) {
    const int i0 = first_node(xi);  // nodes i0 .. i0 + 2
    factors(xi - (i0 + 1), w, dw);
    return i0;
  }
  /// The weights and slopes (per unit xi) of nodes i0 .. i0 + 2 at r = xi - (i0 + 1) in [-1/2, 1/2),
  /// for a double or for the lanes of several particles (core/lanes.hpp).
  template <class T>
  static void factors(const T& r, T* w, T* dw) {
    const T a = 0.5 - r, b = 0.5 + r;
    w[0] = 0.5 * a * a;
    w[1] = 0.75 - r * r;
    w[2] = 0.5 * b * b;
    dw[0] = -a;
    dw[1] = -2.0 * r;
    dw[2] = b;
  }
};

/// Uniform cubic B-spline, support [-2, 2] (Gong 2015 eq. (5.1); the per-particle weights of
/// §5.4 with the typo "3/2" read as 2/3, extraction §4.2). With the fold below, the basis next to
/// the grid edge is that of the open (clamped) knot vector {0,0,0,0,1,2,...,c,c,c,c}, whose two
/// extra control points (Greville abscissae h/3 and c - h/3) are expressed through the edge nodes
/// by linear interpolation: N_0 = B_0 + 2/3 B_1, N_1 = B_2 + 1/3 B_1 (tested against Cox-de Boor
/// in tests/unit/test_shape_family.cpp). N_0 = 1 on the edge, every weight is non-negative.
struct CubicKernel {
  static constexpr int point_width = 4;
  static constexpr double radius = 2.0;

  static double value(double r) {
    const double a = std::abs(r);
    if (a < 1.0) return 2.0 / 3.0 - a * a + 0.5 * a * a * a;
    if (a < 2.0) return (2.0 - a) * (2.0 - a) * (2.0 - a) / 6.0;
    return 0.0;
  }
  static double integral(double r) {
    if (r <= -2.0) return 0.0;
    if (r <= -1.0) return std::pow(2.0 + r, 4) / 24.0;
    if (r <= 0.0) return 0.5 - integral_core(-r);
    if (r <= 1.0) return 0.5 + integral_core(r);
    if (r <= 2.0) return 1.0 - std::pow(2.0 - r, 4) / 24.0;
    return 1.0;
  }
  static int first_node(double xi) { return floor_to_int(xi) - 1; }
  static int point(double xi, double* w, double* dw) {
    const int cell = floor_to_int(xi);
    const double t = xi - cell, s = 1.0 - t;
    w[0] = s * s * s / 6.0;
    w[1] = 2.0 / 3.0 - t * t + 0.5 * t * t * t;
    w[2] = 2.0 / 3.0 - s * s + 0.5 * s * s * s;
    w[3] = t * t * t / 6.0;
    dw[0] = -0.5 * s * s;
    dw[1] = -2.0 * t + 1.5 * t * t;
    dw[2] = 2.0 * s - 1.5 * s * s;
    dw[3] = 0.5 * t * t;
    return cell - 1;  // nodes cell - 1 .. cell + 2
  }

 private:
  static double integral_core(double a) {
    return 2.0 / 3.0 * a - a * a * a / 3.0 + a * a * a * a / 8.0;
  }  // int_0^a
};

/// Largest stencil width any basis uses (for scratch arrays).
inline constexpr int kMaxKernelWidth = 5;

/// Folds the weights of window nodes i0 .. i0 + n - 1 that lie outside [0, cells] onto the edge
/// nodes by linear extrapolation (see the file comment) and returns the lowest node of the new
/// window, which lies inside [0, cells]. Needs cells >= n - 1.
inline int fold_to_grid(int i0, int n, int cells, double* w, double* dw) {
  if (i0 >= 0 && i0 + n - 1 <= cells) return i0;
  const int s = std::clamp(i0, 0, cells - n + 1);
  double nw[kMaxKernelWidth] = {}, nd[kMaxKernelWidth] = {};
  for (int k = 0; k < n; ++k) {
    const int j = i0 + k;
    if (j < 0) {  // u_j = (1 - j) u_0 + j u_1
      nw[0 - s] += (1 - j) * w[k];
      nd[0 - s] += (1 - j) * dw[k];
      nw[1 - s] += j * w[k];
      nd[1 - s] += j * dw[k];
    } else if (j > cells) {  // u_j = (1 + j - c) u_c - (j - c) u_{c-1}
      nw[cells - s] += (1 + j - cells) * w[k];
      nd[cells - s] += (1 + j - cells) * dw[k];
      nw[cells - 1 - s] -= (j - cells) * w[k];
      nd[cells - 1 - s] -= (j - cells) * dw[k];
    } else {
      nw[j - s] += w[k];
      nd[j - s] += dw[k];
    }
  }
  std::copy_n(nw, n, w);
  std::copy_n(nd, n, dw);
  return s;
}

/// The lowest node of the folded point window at xi (monotone in xi), without the weights.
template <class Kernel>
inline int point_window_start(double xi, int cells) {
  return std::clamp(Kernel::first_node(xi), 0, cells - Kernel::point_width + 1);
}

/// A grid function evaluated at a point: the kernel's point window, folded into the grid.
template <class Kernel>
inline int point_on_grid(double xi, int cells, double* w, double* dw) {
  const int i0 = Kernel::point(xi, w, dw);
  return fold_to_grid(i0, Kernel::point_width, cells, w, dw);
}

/// GIMP average of a grid function over the particle domain [xi - l, xi + l] (Gong 2015 eqs.
/// (6.4)-(6.5)): S_j = (1/2l) int K(s - j) ds = (I(xi + l - j) - I(xi - l - j)) / 2l and
/// dS_j/dxi = (K(xi + l - j) - K(xi - l - j)) / 2l. For the hat this is the closed form of §6.3
/// (extraction §5.2, with the sign of the last gradient branch corrected to -(h + l - d)/(2hl)).
/// Width point_width + 1 covers the support for l <= 1/2; the caller caps l.
template <class Kernel>
inline int domain_on_grid(double xi, double l, int cells, double* w, double* dw) {
  constexpr int n = Kernel::point_width + 1;
  const int i0 = floor_to_int(xi - l - Kernel::radius) + 1;
  const double inv = 0.5 / l;
  for (int k = 0; k < n; ++k) {
    const double d = xi - (i0 + k);
    w[k] = (Kernel::integral(d + l) - Kernel::integral(d - l)) * inv;
    dw[k] = (Kernel::value(d + l) - Kernel::value(d - l)) * inv;
  }
  return fold_to_grid(i0, n, cells, w, dw);
}

}  // namespace matpoint
