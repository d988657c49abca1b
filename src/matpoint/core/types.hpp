// Small fixed-size vectors and matrices used throughout matpoint.
#pragma once

#include <Eigen/Dense>

#include <cstddef>
#include <cstdint>

namespace matpoint {

template <int D> using Vec = Eigen::Matrix<double, D, 1>;
template <int D> using Mat = Eigen::Matrix<double, D, D>;

/// Flat index of a grid node or cell.
using Index = std::int64_t;

/// Loops shorter than this run on one thread: below it, waking threads costs more than it saves.
inline constexpr std::ptrdiff_t kParallelMinimum = 4096;

}  // namespace matpoint
