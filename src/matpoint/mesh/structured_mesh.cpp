// Structured rectangle and box meshes (structured_mesh.hpp).
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

/// Structured mesh of element type E (Q4, Q9, Hex8) with tensor local numbering E::kTensor.
template <class E>
Mesh<E::kDim> structured(const std::array<AxisSpacing, E::kDim>& axes) {
  constexpr int D = E::kDim, p = E::kDegree;
  Mesh<D> mesh;
  mesh.shape = E::kShape;
  mesh.nodes_per_element = E::kNodes;
  std::array<std::vector<double>, D> lat;
  std::array<Index, D> nn{}, ne{};
  for (int a = 0; a < D; ++a) {
    require(axes[a].cells() >= 1, "every axis needs at least one cell");
    for (int c = 0; c < axes[a].cells(); ++c)
      require(axes[a].breaks[c + 1] > axes[a].breaks[c], "breaks must ascend");
    lat[a] = lattice(axes[a], p);
    nn[a] = static_cast<Index>(lat[a].size());
    ne[a] = axes[a].cells();
  }
  auto node_id = [&](const std::array<Index, D>& ijk) {
    Index id = 0;
    for (int a = D - 1; a >= 0; --a) id = id * nn[a] + ijk[a];
    return id;
  };
  // Nodes, x fastest.
  Index total = 1;
  for (int a = 0; a < D; ++a) total *= nn[a];
  mesh.nodes.resize(total);
  for (Index n = 0; n < total; ++n) {
    Index rest = n;
    for (int a = 0; a < D; ++a) {
      mesh.nodes[n][a] = lat[a][rest % nn[a]];
      rest /= nn[a];
    }
  }
  // Elements, x fastest; sides.
  Index elements = 1;
  for (int a = 0; a < D; ++a) elements *= ne[a];
  for (Index e = 0; e < elements; ++e) {
    std::array<Index, D> cell{};
    Index rest = e;
    for (int a = 0; a < D; ++a) cell[a] = rest % ne[a], rest /= ne[a];
    for (int i = 0; i < E::kNodes; ++i) {
      std::array<Index, D> ijk{};
      for (int a = 0; a < D; ++a) ijk[a] = p * cell[a] + E::kTensor[i][a];
      mesh.connectivity.push_back(node_id(ijk));
    }
    for (int a = 0; a < D; ++a) {
      if (cell[a] == 0) mesh.boundary_faces[kSides[a][0]].push_back({e, face_on_side<E>(a, -1.0)});
      if (cell[a] == ne[a] - 1) mesh.boundary_faces[kSides[a][1]].push_back({e, face_on_side<E>(a, 1.0)});
    }
  }
  for (Index n = 0; n < total; ++n) {
    Index rest = n;
    for (int a = 0; a < D; ++a) {
      const Index i = rest % nn[a];
      rest /= nn[a];
      if (i == 0) mesh.node_sets[kSides[a][0]].push_back(n);
      if (i == nn[a] - 1) mesh.node_sets[kSides[a][1]].push_back(n);
    }
  }
  return mesh;
}

}  // namespace

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

Mesh<2> structured_rectangle(ElementShape shape, const AxisSpacing& x, const AxisSpacing& y) {
  if (shape == ElementShape::Q4) return structured<Q4>({x, y});
  if (shape == ElementShape::Q9) return structured<Q9>({x, y});
  throw std::invalid_argument(std::string("structured_rectangle: element ") + shape_name(shape) +
                              " is not a quadrilateral (q4 or q9 expected)");
}

Mesh<3> structured_box(const AxisSpacing& x, const AxisSpacing& y, const AxisSpacing& z) {
  return structured<Hex8>({x, y, z});
}

}  // namespace matpoint::mesh
