// Element residual and Jacobian by forward-mode automatic differentiation, for any residual written
// as a template on the scalar type: residual(const S* u, S* r) over the element's N dofs. Generic
// (every implicit formulation uses it); the formulations only write residuals.
//
// Scalar choice, measured by bench/bench_ad.cpp (one Q9 element, 9 particles, the residual of
// implicit/particle_newmark/particle_residual.hpp + its 18 x 18 Jacobian; 2-core AMD EPYC VM, GCC 12,
// -O3 -march=native, one thread, median of 3, 2026-11-24):
//   double residual only                               0.44 us per element
//   Eigen AutoDiffScalar<Matrix<double, 18, 1>>        7.1 - 7.7 us
//   our Dual<18>, unpadded std::array<double, 18>      26 us (store-forwarding stalls: 16 + 2 lanes)
//   our Dual<18>, padded to 24 and 64-byte aligned     7.3 us
//   ... plus the fused acc += a * b (add_product)      6.1 us  (0.68 us per particle, 1.5 M/s)
// so Dual<N> it is: 15-20 % faster than AutoDiffScalar, no dependence on Eigen's unsupported
// module, and the same code paths in the residual (add_product) for double.
#pragma once

#include <array>

#include "matpoint/core/dual.hpp"

namespace matpoint::implicit {

/// The AD scalar of an element with N dofs.
template <int N>
using AdScalar = Dual<N>;

/// r = residual(u) and K = dr/du (row-major, K[i * N + j] = dr_i / du_j) by forward-mode AD.
template <int N, class Residual>
void residual_and_jacobian(const double* u, Residual&& residual, double* r, double* K) {
  using S = AdScalar<N>;
  std::array<S, N> us, rs;
  for (int i = 0; i < N; ++i) {
    us[static_cast<std::size_t>(i)] = S::variable(u[i], i);
    rs[static_cast<std::size_t>(i)] = S(0.0);
  }
  residual(us.data(), rs.data());
  for (int i = 0; i < N; ++i) {
    const S& ri = rs[static_cast<std::size_t>(i)];
    r[i] = ri.v;
    for (int j = 0; j < N; ++j) K[i * N + j] = ri.d[static_cast<std::size_t>(j)];
  }
}

/// r = residual(u) in plain double (line searches and finite differences need no Jacobian).
template <int N, class Residual>
void residual_only(const double* u, Residual&& residual, double* r) {
  for (int i = 0; i < N; ++i) r[i] = 0.0;
  residual(u, r);
}

}  // namespace matpoint::implicit
