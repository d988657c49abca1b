// Small fixed-size vectors and matrices used throughout matpoint.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace matpoint {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;

/// Flat index of a grid node or cell.
using Index = std::int64_t;

/// floor(x) as an int for a coordinate in cell units. x is first limited to +/- 2^28 cells (NaN to
/// the lower end): converting an out-of-range double to int is undefined behaviour, and a diverging
/// run can put a particle or a CPDI domain corner 1e10 cells away before a guard stops it (found by
/// UBSan in a stability scan). In any real grid this is plain floor.
inline int floor_to_int(double x) {
  constexpr double kLimit = 268435456.0;  // 2^28
  if (!(x > -kLimit)) return -static_cast<int>(kLimit);
  if (!(x < kLimit)) return static_cast<int>(kLimit);
  return static_cast<int>(std::floor(x));
}

/// Loops shorter than this run on one thread: below it, waking threads costs more than it saves.
inline constexpr std::ptrdiff_t kParallelMinimum = 4096;

}  // namespace matpoint
