// Several particles at once: a D x D matrix whose entries are SIMD lanes, one particle per lane
// (std::experimental::simd, libstdc++'s Parallelism TS v2). The per-particle passes whose cost is
// arithmetic, not memory traffic (the F update, the neo-Hookean stress: bench/README.md, sessions
// 24 and 30), run their formulas on kLanes particles per instruction.
//
// Bitwise rule: every lane performs the IEEE operations of the scalar Eigen code in the same order,
// so a particle's result does not depend on whether it went through the lanes or the scalar path
// (the remainder, a batch with a mixed material) nor on the thread count. Eigen's fixed-size
// products and sums reduce by halves: a0 + a1 for two terms, a0 + (a1 + a2) for three
// (Redux.h, redux_novec_unroller); `sum_in_eigen_order` repeats that; tests/unit/test_lanes.cpp
// compares both paths with ==.
#pragma once

#include <experimental/simd>

#include "matpoint/core/types.hpp"

namespace matpoint {

namespace stdx = std::experimental;

/// Particles per batch: 4 doubles (one AVX2 register). Wider lanes (AVX-512's 8) measured no faster
/// on the development machine and leave longer scalar remainders.
inline constexpr int kLanes = 4;
using Lanes = stdx::fixed_size_simd<double, kLanes>;
using LaneMask = stdx::fixed_size_simd_mask<double, kLanes>;

/// a0 + a1 (D = 2), a0 + (a1 + a2) (D = 3): Eigen's order for a fixed-size sum of D terms.
template <int D, class T>
T sum_in_eigen_order(const T* a) {
  if constexpr (D == 1)
    return a[0];
  else if constexpr (D == 2)
    return a[0] + a[1];
  else
    return a[0] + (a[1] + a[2]);
}

/// A D x D matrix of lanes: entry (i, j) of kLanes particles' matrices.
template <int D>
struct LaneMatrix {
  Lanes entry[D][D];

  Lanes& operator()(int i, int j) { return entry[i][j]; }
  const Lanes& operator()(int i, int j) const { return entry[i][j]; }

  /// Matrices first[0 .. kLanes) (one particle per lane).
  static LaneMatrix load(const Mat<D>* first) {
    LaneMatrix m;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) m.entry[i][j] = Lanes([&](auto lane) { return first[lane](i, j); });
    return m;
  }
  void store(Mat<D>* first) const {
    for (int lane = 0; lane < kLanes; ++lane)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) first[lane](i, j) = entry[i][j][lane];
  }
  /// this * s, entry by entry (Eigen's matrix * scalar).
  LaneMatrix operator*(const Lanes& s) const {
    LaneMatrix m;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) m.entry[i][j] = entry[i][j] * s;
    return m;
  }
  /// The matrix product in Eigen's coefficient-based order (small fixed sizes).
  LaneMatrix operator*(const LaneMatrix& b) const {
    LaneMatrix m;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        Lanes terms[D];
        for (int k = 0; k < D; ++k) terms[k] = entry[i][k] * b.entry[k][j];
        m.entry[i][j] = sum_in_eigen_order<D>(terms);
      }
    return m;
  }
  [[nodiscard]] LaneMatrix transposed() const {
    LaneMatrix m;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) m.entry[i][j] = entry[j][i];
    return m;
  }
  /// The determinant as Eigen's determinant() forms it (LU/Determinant.h: the 2 x 2 formula, the
  /// 3 x 3 expansion along the first row).
  [[nodiscard]] Lanes determinant() const {
    const auto& m = entry;
    if constexpr (D == 1) {
      return m[0][0];
    } else if constexpr (D == 2) {
      return m[0][0] * m[1][1] - m[1][0] * m[0][1];
    } else {
      auto minor = [&](int a, int b, int c) { return m[0][a] * (m[1][b] * m[2][c] - m[1][c] * m[2][b]); };
      return minor(0, 1, 2) - minor(1, 0, 2) + minor(2, 0, 1);
    }
  }
  /// this += b in the lanes of `where` only (the others keep their values bitwise).
  void add_where(const LaneMask& where, const LaneMatrix& b) {
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) stdx::where(where, entry[i][j]) += b.entry[i][j];
  }
  /// The infinity norm (largest absolute row sum), as Eigen's cwiseAbs().rowwise().sum().maxCoeff().
  [[nodiscard]] Lanes infinity_norm() const {
    Lanes rows[D];
    for (int i = 0; i < D; ++i) {
      Lanes magnitudes[D];
      for (int j = 0; j < D; ++j) magnitudes[j] = stdx::abs(entry[i][j]);
      rows[i] = sum_in_eigen_order<D>(magnitudes);
    }
    // maxCoeff reduces by halves too, with std::max's (a < b) ? b : a.
    auto larger = [](const Lanes& a, const Lanes& b) {
      Lanes r = a;
      stdx::where(a < b, r) = b;
      return r;
    };
    if constexpr (D == 1)
      return rows[0];
    else if constexpr (D == 2)
      return larger(rows[0], rows[1]);
    else
      return larger(rows[0], larger(rows[1], rows[2]));
  }
};

}  // namespace matpoint
