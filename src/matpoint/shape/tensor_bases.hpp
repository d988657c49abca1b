// One-dimensional bases whose D-dimensional shape functions are tensor products:
// N_i(x) = prod_a phi(x_a) and grad N_i = (phi'(x_0) phi(x_1) ..., phi(x_0) phi'(x_1) ..., ...).
// A basis maps a particle coordinate xi (in cells, measured from the grid origin) to the integer
// coordinate of its lowest node and the `width` weights and derivatives (per unit xi).
#pragma once

#include <cmath>

#include "matpoint/core/lanes.hpp"
#include "matpoint/shape/kernels.hpp"

namespace matpoint {

/// How a tensor basis sizes the particle domain it averages over (GIMP family).
enum class DomainWidth {
  None,      // point basis: weights at the particle position
  Initial,   // uGIMP: half-width l = l0 = size0 / 2, fixed
  Stretched  // cpGIMP: half-width l = |F_aa| l0 per axis (Gong 2015 §6.3, extraction A20)
};

/// Classic MPM: piecewise-linear hat functions on the cell that contains the particle.
struct LinearBasis {
  static constexpr int width = 2;
  static constexpr int ghost_layers = 0;
  static constexpr const char* name = "linear";
  static constexpr DomainWidth domain = DomainWidth::None;

  static int evaluate(double xi, int cells, double* w, double* dw) {
    int i0 = HatKernel::first_node(xi);
    i0 = i0 < 0 ? 0 : (i0 >= cells ? cells - 1 : i0);  // a particle on the max face uses the last cell
    HatKernel::cell_weights(xi - i0, w, dw);
    return i0;
  }
  /// evaluate() for kLanes coordinates whose cells are all inside the grid (else false, nothing
  /// set, and the caller uses evaluate()): the same operations per lane (core/lanes.hpp).
  static bool evaluate_lanes(const Lanes& xi, int cells, Lanes* w, Lanes* dw, Lanes& lowest) {
    const Lanes i0 = stdx::floor(xi);                                 // floor_to_int(xi), exact in double
    if (!stdx::all_of(i0 >= 0.0 && i0 <= cells - 1.0)) return false;  // the clamp would act (or NaN)
    const Lanes r = xi - i0;
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = Lanes(-1.0);
    dw[1] = Lanes(1.0);
    lowest = i0;
    return true;
  }
};

/// Quadratic B-spline centred on nodes (support 1.5 cells), modified next to the domain edge so
/// that no node outside the domain is needed: the weight of the missing node -1 is folded into
/// nodes 0 and 1 as phi_0 += 2 phi_{-1}, phi_1 -= phi_{-1} (the same at the max edge). This keeps
/// partition of unity and linear reproduction, and in the boundary half-cell the kernel becomes
/// phi_0 = 1 - xi, phi_1 = xi, which joins the interior kernel with continuous value and slope
/// (the boundary-modified kernel of Steffen, Kirby & Berzins 2008). A node on a fixed face then
/// carries the whole weight at the face, so the condition holds there exactly.
struct QuadraticBSplineBasis {
  static constexpr int width = 3;
  static constexpr int ghost_layers = 0;
  static constexpr const char* name = "bspline2";
  static constexpr DomainWidth domain = DomainWidth::None;

  static int evaluate(double xi, int cells, double* w, double* dw) {
    int i0 = QuadraticKernel::first_node(xi);  // nodes i0, i0+1, i0+2
    QuadraticKernel::factors(xi - (i0 + 1), w, dw);
    if (i0 < 0) {  // node -1 missing: nodes 0, 1, 2 carry (phi_0 + 2 phi_-1, phi_1 - phi_-1, 0)
      fold(w, dw, 0, 1, 2);
      i0 = 0;
    } else if (i0 + 2 > cells) {  // node cells + 1 missing: nodes cells - 2 .. cells
      fold(w, dw, 2, 1, 0);
      i0 = cells - 2;
    }
    return i0;
  }
  /// evaluate() for kLanes coordinates whose three nodes are all inside the grid (else false,
  /// nothing set, and the caller uses evaluate(), which folds): the same operations per lane.
  static bool evaluate_lanes(const Lanes& xi, int cells, Lanes* w, Lanes* dw, Lanes& lowest) {
    const Lanes centre = stdx::floor(xi + 0.5);  // i0 + 1, exact in double
    // No fold: i0 >= 0 and i0 + 2 <= cells (false for a NaN too).
    if (!stdx::all_of(centre >= 1.0 && centre <= cells - 1.0)) return false;
    QuadraticKernel::factors(Lanes(xi - centre), w, dw);
    lowest = centre - 1.0;
    return true;
  }

 private:
  /// Moves the weight of slot `gone` onto `edge` (x2) and `inner` (x-1), then shifts the three
  /// slots one node inwards.
  static void fold(double* w, double* dw, int gone, int edge, int inner) {
    const double wg = w[gone], dg = dw[gone];
    double nw[3], nd[3];
    nw[edge] = w[edge] + 2.0 * wg;
    nd[edge] = dw[edge] + 2.0 * dg;
    nw[inner] = w[inner] - wg;
    nd[inner] = dw[inner] - dg;
    const int shift = gone == 0 ? -1 : 1;  // slot k holds node (k + shift) of the shifted window
    for (int k = 0; k < 3; ++k) {
      const int from = k - shift;  // old slot whose node becomes new slot k
      w[k] = from >= 0 && from < 3 && from != gone ? nw[from] : 0.0;
      dw[k] = from >= 0 && from < 3 && from != gone ? nd[from] : 0.0;
    }
  }
};

/// Cubic B-spline (support 2 cells), boundary-modified by the fold of kernels.hpp: next to the
/// grid edge it is the open (clamped) knot vector basis, with N_0 = 1 on the edge face.
struct CubicBSplineBasis {
  static constexpr int width = CubicKernel::point_width;
  static constexpr int ghost_layers = 0;
  static constexpr const char* name = "bspline3";
  static constexpr DomainWidth domain = DomainWidth::None;

  static int evaluate(double xi, int cells, double* w, double* dw) {
    return point_on_grid<CubicKernel>(xi, cells, w, dw);
  }
};

/// GIMP weights (Bardenhagen & Kober 2004; Gong 2015 §6.2-6.3, eqs. (6.4)-(6.5)): the grid
/// function `Kernel` averaged over the particle's axis-aligned domain [x - l, x + l] per axis.
///   HatKernel + Initial       uGIMP
///   HatKernel + Stretched     cpGIMP (l = |F_aa| l0, capped at h/2 as Gong's formula assumes)
///   QuadraticKernel + Initial B2GIMP (Nairn 2026 §2.1: GIMP with quadratic B-spline grid functions)
/// The half-width l (in cells) comes from the particle; the part of the domain past the grid edge
/// is integrated against the linearly extrapolated basis (fold), so partition of unity holds.
template <class Kernel, DomainWidth Kind>
struct GimpBasis {
  static constexpr int width = Kernel::point_width + 1;
  static constexpr int ghost_layers = 0;
  static constexpr DomainWidth domain = Kind;
  /// Smallest half-width in cells: below it the average is computed at this width (the
  /// difference quotient of the antiderivative would lose digits, error ~ 1e-16 / l).
  static constexpr double min_half_width = 1e-6;

  static int evaluate(double xi, double l, int cells, double* w, double* dw) {
    return domain_on_grid<Kernel>(xi, l, cells, w, dw);
  }
};

using UGimpBasis = GimpBasis<HatKernel, DomainWidth::Initial>;
using CpGimpBasis = GimpBasis<HatKernel, DomainWidth::Stretched>;
using B2GimpBasis = GimpBasis<QuadraticKernel, DomainWidth::Initial>;

}  // namespace matpoint
