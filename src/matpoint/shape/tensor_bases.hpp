// One-dimensional bases whose D-dimensional shape functions are tensor products:
// N_i(x) = prod_a phi(x_a) and grad N_i = (phi'(x_0) phi(x_1) ..., phi(x_0) phi'(x_1) ..., ...).
// A basis maps a particle coordinate xi (in cells, measured from the grid origin) to the integer
// coordinate of its lowest node and the `width` weights and derivatives (per unit xi).
#pragma once

#include <cmath>

namespace matpoint {

/// Classic MPM: piecewise-linear hat functions on the cell that contains the particle.
struct LinearBasis {
  static constexpr int width = 2;
  static constexpr int ghost_layers = 0;
  static constexpr const char* name = "linear";

  static int evaluate(double xi, int cells, double* w, double* dw) {
    int i0 = static_cast<int>(std::floor(xi));
    i0 = i0 < 0 ? 0 : (i0 >= cells ? cells - 1 : i0);  // a particle on the max face uses the last cell
    const double r = xi - i0;
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = -1.0;
    dw[1] = 1.0;
    return i0;
  }
};

/// Uniform quadratic B-spline centred on nodes (support 1.5 cells). Next to the domain edge it
/// reaches one ghost node layer, so partition of unity and linear reproduction hold everywhere
/// inside the domain (Steffen, Kirby & Berzins 2008 use the same kernel).
struct QuadraticBSplineBasis {
  static constexpr int width = 3;
  static constexpr int ghost_layers = 1;
  static constexpr const char* name = "bspline2";

  static int evaluate(double xi, int /*cells*/, double* w, double* dw) {
    const int i0 = static_cast<int>(std::floor(xi + 0.5)) - 1;  // nodes i0, i0+1, i0+2
    const double r = xi - (i0 + 1);                               // in [-1/2, 1/2)
    const double a = 0.5 - r, b = 0.5 + r;
    w[0] = 0.5 * a * a;
    w[1] = 0.75 - r * r;
    w[2] = 0.5 * b * b;
    dw[0] = -a;
    dw[1] = -2.0 * r;
    dw[2] = b;
    return i0;
  }
};

}  // namespace matpoint
