// Linear systems with known properties for the linear-solver tests (tests/unit/test_implicit_solvers.cpp,
// tests/mpi/test_petsc_solver.cpp).
#pragma once

#include <vector>

#include "matpoint/implicit/sparse_assembly.hpp"

namespace matpoint::test {

/// -Laplace + upwind convection on an m x m grid: nonsymmetric, nonsingular (diagonally dominant).
inline implicit::SparseMatrix convection_diffusion(int m) {
  std::vector<Eigen::Triplet<double, int>> t;
  const auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + 3.0);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0 - 2.0);
      if (i + 1 < m) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0 - 1.0);
      if (j + 1 < m) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  implicit::SparseMatrix a(m * m, m * m);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

}  // namespace matpoint::test
