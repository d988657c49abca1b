// How a structured T3 mesh splits each rectangular cell into triangles (mesh.diagonal in the
// input; docs/input.md). The mesh generator (structured_mesh.cpp) and the particle placement at the
// triangles' Gauss points (particles/generators.cpp, bodies[].placement "gauss") share it, so the
// particles sit in the triangles the mesh has. Header-only and free of the mesh types: io/spec.hpp
// holds the choice.
#pragma once

#include <array>
#include <span>

namespace matpoint::mesh {

/// rising: every cell cut along the diagonal from its (x-, y-) to its (x+, y+) corner; falling:
/// from (x+, y-) to (x-, y+); alternating: rising where i + j is even and falling where it is odd
/// (cell (i, j): the i-th along x, the j-th along y), so no direction is preferred over the
/// mesh; crossed: both diagonals, four triangles about a node at the cell's centre.
enum class TrianglePattern { Rising, Falling, Alternating, Crossed };

/// The corners of a cell: 0 (x-, y-), 1 (x+, y-), 2 (x+, y+), 3 (x-, y+), and 4 the centre
/// (crossed only).
inline constexpr std::array<std::array<double, 2>, 5> kCellCorner{
    {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}}};

/// The triangles of cell (i, j) as cell-corner ids, counter-clockwise (positive area).
inline std::span<const std::array<int, 3>> cell_triangles(TrianglePattern pattern, long i, long j) {
  static constexpr std::array<std::array<int, 3>, 2> kRising{{{0, 1, 2}, {0, 2, 3}}};
  static constexpr std::array<std::array<int, 3>, 2> kFalling{{{0, 1, 3}, {1, 2, 3}}};
  static constexpr std::array<std::array<int, 3>, 4> kCrossed{{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}};
  switch (pattern) {
    case TrianglePattern::Rising:
      return kRising;
    case TrianglePattern::Falling:
      return kFalling;
    case TrianglePattern::Alternating:
      return (i + j) % 2 == 0 ? std::span<const std::array<int, 3>>(kRising) : kFalling;
    case TrianglePattern::Crossed:
      return kCrossed;
  }
  return kRising;
}

}  // namespace matpoint::mesh
