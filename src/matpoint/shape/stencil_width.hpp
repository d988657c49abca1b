// How many cells a basis needs per direction: its stencil spans that many cells plus one node, and a
// grid with fewer cells cannot hold one stencil (checked by the input validator, exit 2).
#pragma once

#include "matpoint/io/spec.hpp"

namespace matpoint {

/// Fewest cells per direction for which a basis's stencils fit on the grid (stencil width - 1).
constexpr int minimum_cells(ShapeKind shape) {
  switch (shape) {
    case ShapeKind::BSpline2:
    case ShapeKind::UGIMP:
    case ShapeKind::CpGIMP:
    case ShapeKind::B2CPDI:
      return 2;
    case ShapeKind::BSpline3:
    case ShapeKind::B2GIMP:
      return 3;
    default:
      return 1;
  }
}

}  // namespace matpoint
