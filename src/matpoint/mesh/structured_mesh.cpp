// Structured rectangle (Q4, Q9, T3) and box (Hex8) meshes (structured_mesh.hpp).
#include "matpoint/mesh/structured_mesh.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace matpoint::mesh {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("structured mesh: " + what);
}

/// Lattice coordinates of one axis for element order p: the breaks, and for p = 2 the cell midpoints.
std::vector<double> lattice(const AxisSpacing& s, int order) {
  std::vector<double> out;
  for (int c = 0; c < s.cells(); ++c) {
    out.push_back(s.breaks[c]);
    if (order == 2) out.push_back(0.5 * (s.breaks[c] + s.breaks[c + 1]));
  }
  out.push_back(s.breaks.back());
  return out;
}

/// The local face of element type E lying on the reference side xi_axis = sign (sign = +-1).
template <class E>
int face_on_side(int axis, double sign) {
  const auto ref = E::reference_nodes();
  const auto faces = E::faces();
  for (int f = 0; f < E::kFaces; ++f) {
    bool on = true;
    for (int i : faces[f]) on = on && ref(i, axis) == sign;
    if (on) return f;
  }
  throw std::logic_error("structured mesh: no face on a reference side");
}

/// Side names per axis: {low, high}.
constexpr std::array<std::array<const char*, 2>, 3> kSides = {
    {{"left", "right"}, {"bottom", "top"}, {"back", "front"}}};

/// A D-dimensional box of counts: flat index (first axis fastest) <-> multi-index.
template <int D>
struct Lattice {
  std::array<Index, D> size{};
  Index total() const {
    Index n = 1;
    for (Index s : size) n *= s;
    return n;
  }
  Index flat(const std::array<Index, D>& i) const {
    Index id = 0;
    for (int a = D - 1; a >= 0; --a) id = id * size[a] + i[a];
    return id;
  }
  std::array<Index, D> split(Index flat) const {
    std::array<Index, D> i{};
    for (int a = 0; a < D; ++a) i[a] = flat % size[a], flat /= size[a];
    return i;
  }
};

/// Nodes on the lattice of per-axis coordinates, and the side node sets.
template <int D>
void structured_nodes(const std::array<std::vector<double>, D>& coordinates, const Lattice<D>& nodes,
                      Mesh<D>& mesh) {
  mesh.nodes.resize(nodes.total());
  for (Index n = 0; n < nodes.total(); ++n) {
    const auto i = nodes.split(n);
    for (int a = 0; a < D; ++a) {
      mesh.nodes[n][a] = coordinates[a][i[a]];
      if (i[a] == 0) mesh.node_sets[kSides[a][0]].push_back(n);
      if (i[a] == nodes.size[a] - 1) mesh.node_sets[kSides[a][1]].push_back(n);
    }
  }
}

/// Elements (cell (c_a): lattice nodes p c_a + tensor index of each local node) and side faces.
template <class E>
void structured_elements(const Lattice<E::kDim>& cells, const Lattice<E::kDim>& nodes, Mesh<E::kDim>& mesh) {
  constexpr int D = E::kDim;
  for (Index e = 0; e < cells.total(); ++e) {
    const auto cell = cells.split(e);
    for (int i = 0; i < E::kNodes; ++i) {
      std::array<Index, D> node{};
      for (int a = 0; a < D; ++a) node[a] = E::kDegree * cell[a] + E::kTensor[i][a];
      mesh.connectivity.push_back(nodes.flat(node));
    }
    for (int a = 0; a < D; ++a) {
      if (cell[a] == 0) mesh.boundary_faces[kSides[a][0]].push_back({e, face_on_side<E>(a, -1.0)});
      if (cell[a] == cells.size[a] - 1)
        mesh.boundary_faces[kSides[a][1]].push_back({e, face_on_side<E>(a, 1.0)});
    }
  }
}

/// Structured mesh of element type E (Q4, Q9, Hex8) with tensor local numbering E::kTensor.
template <class E>
Mesh<E::kDim> structured(const std::array<AxisSpacing, E::kDim>& axes) {
  constexpr int D = E::kDim;
  Mesh<D> mesh;
  mesh.shape = E::kShape;
  mesh.nodes_per_element = E::kNodes;
  std::array<std::vector<double>, D> coordinates;
  Lattice<D> cells, nodes;
  for (int a = 0; a < D; ++a) {
    require(axes[a].cells() >= 1, "every axis needs at least one cell");
    for (int c = 0; c < axes[a].cells(); ++c)
      require(axes[a].breaks[c + 1] > axes[a].breaks[c], "breaks must ascend");
    coordinates[a] = lattice(axes[a], E::kDegree);
    nodes.size[a] = static_cast<Index>(coordinates[a].size());
    cells.size[a] = axes[a].cells();
  }
  structured_nodes<D>(coordinates, nodes, mesh);
  structured_elements<E>(cells, nodes, mesh);
  return mesh;
}

/// The local edge of triangle `t` (cell-corner ids) lying on the cell side (axis, sign), or -1:
/// T3 edge k joins its nodes k and k + 1 (mod 3).
int triangle_edge_on_side(const std::array<int, 3>& t, int axis, int sign) {
  const double at = sign < 0 ? 0.0 : 1.0;
  for (int k = 0; k < 3; ++k) {
    const auto& a = kCellCorner[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
    const auto& b = kCellCorner[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])];
    if (a[static_cast<std::size_t>(axis)] == at && b[static_cast<std::size_t>(axis)] == at) return k;
  }
  return -1;
}

/// Structured T3 mesh: the Q4 lattice's nodes (numbered as structured<Q4>), then for the crossed
/// pattern one node per cell centre (cell order); each cell's triangles (cell_triangles) in cell
/// order, x fastest.
Mesh<2> structured_triangles(const AxisSpacing& x, const AxisSpacing& y, TrianglePattern pattern) {
  Mesh<2> mesh = structured<Q4>({x, y});  // nodes, side node sets; its elements are replaced
  mesh.shape = ElementShape::T3;
  mesh.nodes_per_element = T3::kNodes;
  mesh.connectivity.clear();
  mesh.boundary_faces.clear();
  const Index nx = x.cells(), ny = y.cells();
  const Index lattice_nodes = (nx + 1) * (ny + 1);
  for (Index j = 0; j < ny; ++j)
    for (Index i = 0; i < nx; ++i) {
      const std::array<Index, 5> corner{j * (nx + 1) + i, j * (nx + 1) + i + 1, (j + 1) * (nx + 1) + i + 1,
                                        (j + 1) * (nx + 1) + i, lattice_nodes + j * nx + i};
      if (pattern == TrianglePattern::Crossed)
        mesh.nodes.push_back(
            Vec<2>(0.5 * (x.breaks[i] + x.breaks[i + 1]), 0.5 * (y.breaks[j] + y.breaks[j + 1])));
      for (const auto& t : cell_triangles(pattern, i, j)) {
        const Index e = mesh.element_count();
        for (int c : t) mesh.connectivity.push_back(corner[static_cast<std::size_t>(c)]);
        const std::array<std::array<bool, 2>, 2> on_side{{{i == 0, i == nx - 1}, {j == 0, j == ny - 1}}};
        for (int axis = 0; axis < 2; ++axis)
          for (int high = 0; high < 2; ++high) {
            if (!on_side[static_cast<std::size_t>(axis)][static_cast<std::size_t>(high)]) continue;
            const int edge = triangle_edge_on_side(t, axis, high == 1 ? 1 : -1);
            if (edge >= 0) mesh.boundary_faces[kSides[axis][high]].push_back({e, edge});
          }
      }
    }
  return mesh;
}

/// Greville abscissae of the quadratic B-splines on the open uniform knots of `s` (equal cells
/// required): the ends, and the cell midpoints between them.
std::vector<double> greville_quadratic(const AxisSpacing& s) {
  const int n = s.cells();
  const double h = (s.breaks.back() - s.breaks.front()) / n;
  for (int c = 0; c < n; ++c)
    require(std::abs(s.breaks[c + 1] - s.breaks[c] - h) <= 1e-9 * h,
            "a B-spline patch needs equal cells along each axis (no grading, no mesh.lines)");
  std::vector<double> out{s.breaks.front()};
  for (int c = 0; c < n; ++c) out.push_back(0.5 * (s.breaks[c] + s.breaks[c + 1]));
  out.push_back(s.breaks.back());
  return out;
}

/// Where cell c of n lies along its axis, as BSpline2::end_along counts (0 inside, 1 first,
/// 2 last, 3 only).
int patch_end(Index c, Index n) { return (c == 0 ? 1 : 0) | (c == n - 1 ? 2 : 0); }

}  // namespace

Mesh<2> structured_bspline2(const AxisSpacing& x, const AxisSpacing& y) {
  Mesh<2> mesh;
  mesh.shape = ElementShape::BSpline2;
  mesh.nodes_per_element = BSpline2::kNodes;
  require(x.cells() >= 1 && y.cells() >= 1, "every axis needs at least one cell");
  const std::array<std::vector<double>, 2> coordinates{greville_quadratic(x), greville_quadratic(y)};
  Lattice<2> nodes, cells;
  for (int a = 0; a < 2; ++a) {
    nodes.size[a] = static_cast<Index>(coordinates[a].size());
    cells.size[a] = nodes.size[a] - 2;
  }
  structured_nodes<2>(coordinates, nodes, mesh);
  for (Index e = 0; e < cells.total(); ++e) {
    const auto cell = cells.split(e);
    for (int iy = 0; iy < 3; ++iy)
      for (int ix = 0; ix < 3; ++ix) mesh.connectivity.push_back(nodes.flat({cell[0] + ix, cell[1] + iy}));
    mesh.variants.push_back(
        BSpline2::variant_of(patch_end(cell[0], cells.size[0]), patch_end(cell[1], cells.size[1])));
  }
  return mesh;
}

AxisSpacing AxisSpacing::uniform(double start, double end, int cells) {
  return geometric(start, end, cells, 1.0);
}

AxisSpacing AxisSpacing::geometric(double start, double end, int cells, double ratio) {
  require(cells >= 1, "an axis needs at least one cell, got " + std::to_string(cells));
  require(end > start, "an axis needs end > start");
  require(ratio > 0.0 && std::isfinite(ratio), "the grading ratio must be positive");
  // Geometric series: sum_k h_0 r^k = h_0 (r^n - 1)/(r - 1) = end - start.
  const double h0 =
      ratio == 1.0 ? (end - start) / cells : (end - start) * (ratio - 1.0) / (std::pow(ratio, cells) - 1.0);
  AxisSpacing s;
  s.breaks.push_back(start);
  double h = h0;
  for (int k = 0; k < cells; ++k, h *= ratio) s.breaks.push_back(s.breaks.back() + h);
  s.breaks.back() = end;  // no drift from the summation
  return s;
}

AxisSpacing AxisSpacing::layers(double start, std::span<const double> sizes) {
  require(!sizes.empty(), "an axis needs at least one layer");
  AxisSpacing s;
  s.breaks.push_back(start);
  for (double h : sizes) {
    require(h > 0.0 && std::isfinite(h), "layer sizes must be positive");
    s.breaks.push_back(s.breaks.back() + h);
  }
  return s;
}

AxisSpacing AxisSpacing::refined(int levels) const {
  require(levels >= 0, "refinement levels must be >= 0");
  const int parts = 1 << levels;
  AxisSpacing s;
  for (int c = 0; c < cells(); ++c)
    for (int k = 0; k < parts; ++k) {
      const double t = static_cast<double>(k) / parts;
      s.breaks.push_back((1.0 - t) * breaks[c] + t * breaks[c + 1]);
    }
  s.breaks.push_back(breaks.back());
  return s;
}

Mesh<2> structured_rectangle(ElementShape shape, const AxisSpacing& x, const AxisSpacing& y,
                             TrianglePattern pattern) {
  if (shape == ElementShape::Q4) return structured<Q4>({x, y});
  if (shape == ElementShape::Q9) return structured<Q9>({x, y});
  if (shape == ElementShape::T3) return structured_triangles(x, y, pattern);
  throw std::invalid_argument(std::string("structured_rectangle: element ") + shape_name(shape) +
                              " is not structured (q4, q9 or t3 expected)");
}

Mesh<3> structured_box(const AxisSpacing& x, const AxisSpacing& y, const AxisSpacing& z) {
  return structured<Hex8>({x, y, z});
}

}  // namespace matpoint::mesh
