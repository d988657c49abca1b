// Structured rectangle (Q4, Q9, T3) and box (Hex8) meshes with graded spacing per direction, as the
// background grids of Aulisa & Capodaglio §6.2 (Test A: 20 x 4 QUAD9 graded towards the plane,
// layer heights bottom -> top 0.867209 * 1.25^k; Test B: 2 x 2 QUAD9 on a unit box). Named sides:
// "left"/"right" (x), "bottom"/"top" (y), "back"/"front" (z), each as a node set and as boundary
// faces. Numbering: nodes on the (order * cells + 1)^D lattice, x fastest, then y, then z; elements
// likewise; Q9 mid-side and centre nodes at the cell midpoints.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "matpoint/mesh/mesh.hpp"
#include "matpoint/mesh/triangle_pattern.hpp"

namespace matpoint::mesh {

/// Cell boundaries along one axis (ascending, cells() + 1 values).
struct AxisSpacing {
  std::vector<double> breaks;

  int cells() const { return static_cast<int>(breaks.size()) - 1; }
  /// `cells` equal cells on [start, end].
  static AxisSpacing uniform(double start, double end, int cells);
  /// `cells` cells on [start, end] whose sizes grow by `ratio` from start to end:
  /// h_k = h_0 ratio^k, h_0 = (end - start)(ratio - 1)/(ratio^cells - 1) (h_0 = (end - start)/cells at 1).
  static AxisSpacing geometric(double start, double end, int cells, double ratio);
  /// Cells of the given sizes, the first starting at `start`.
  static AxisSpacing layers(double start, std::span<const double> sizes);
  /// Every cell split into 2^levels equal cells (what uniform midpoint refinement does to it).
  AxisSpacing refined(int levels) const;
};

/// Structured Q4, Q9 or T3 rectangle mesh on x.breaks x y.breaks; T3: each Q4 cell split into
/// triangles as `pattern` says (triangle_pattern.hpp), the crossed pattern's centre nodes numbered
/// after the lattice's, cell by cell. Throws std::invalid_argument for another shape.
Mesh<2> structured_rectangle(ElementShape shape, const AxisSpacing& x, const AxisSpacing& y,
                             TrianglePattern pattern = TrianglePattern::Alternating);

/// A 2-D patch of C1 quadratic B-splines on uniform open knot vectors (element_types.hpp,
/// BSpline2): one element per cell of x.breaks x y.breaks (which must be equally spaced), its
/// nodes the control points at the Greville abscissae, per axis the breaks' ends and the cell
/// midpoints in between (cells + 2 per axis), x fastest. Node sets name the sides' control points
/// (on the sides); the patch has no boundary faces (its sides are not Lagrange lines). Throws
/// std::invalid_argument for unequal cells.
Mesh<2> structured_bspline2(const AxisSpacing& x, const AxisSpacing& y);

/// Structured Hex8 box mesh on x.breaks x y.breaks x z.breaks.
Mesh<3> structured_box(const AxisSpacing& x, const AxisSpacing& y, const AxisSpacing& z);

}  // namespace matpoint::mesh
