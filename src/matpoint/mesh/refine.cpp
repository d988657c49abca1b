// Uniform midpoint refinement (refine.hpp).
#include "matpoint/mesh/refine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace matpoint::mesh {

namespace {

/// Child k inside its parent's reference element: xi_parent = offset + scale * xi_child.
template <int Dim>
struct ChildMap {
  Vec<Dim> offset;
  double scale;
};

/// Quads/hexes: the 2^D half-size sub-squares (x fastest). Triangles: the three corner triangles
/// and the middle one, turned by 180 degrees (scale -1/2 keeps the orientation in 2-D).
template <class E>
std::vector<ChildMap<E::kDim>> child_maps() {
  std::vector<ChildMap<E::kDim>> out;
  if constexpr (E::kSimplex) {
    out = {
        {Vec<2>(0.0, 0.0), 0.5}, {Vec<2>(0.5, 0.0), 0.5}, {Vec<2>(0.0, 0.5), 0.5}, {Vec<2>(0.5, 0.5), -0.5}};
  } else {
    for (int k = 0; k < (1 << E::kDim); ++k) {
      Vec<E::kDim> s;
      for (int a = 0; a < E::kDim; ++a) s[a] = (k >> a & 1) != 0 ? 0.5 : -0.5;
      out.push_back({s, 0.5});
    }
  }
  return out;
}

/// Topological key of a point of a parent element: (parent corner node id, corner weight * 4096)
/// for the corners of nonzero weight, ascending by id. The weights of refinement points are exact
/// multiples of 1/64, so neighbours sharing an edge or face produce identical keys.
using Key = std::vector<std::pair<Index, int>>;

template <class E>
Key corner_key(std::span<const Index> parent_nodes, const Vec<E::kDim>& xi) {
  const auto w = E::Linear::values(xi);
  Key key;
  for (int c = 0; c < E::kCorners; ++c) {
    const int q = static_cast<int>(std::lround(w[c] * 4096.0));
    if (q != 0) key.emplace_back(parent_nodes[c], q);
  }
  std::sort(key.begin(), key.end());
  return key;
}

/// For each parent face f, the (child, child face) pairs lying on it: every node of the child face
/// has zero weight on the parent corners off face f.
template <class E>
std::vector<std::vector<std::pair<int, int>>> child_faces(const std::vector<ChildMap<E::kDim>>& maps) {
  const auto ref = E::reference_nodes();
  const auto faces = E::faces();
  std::vector<std::vector<std::pair<int, int>>> out(E::kFaces);
  for (int f = 0; f < E::kFaces; ++f) {
    std::array<bool, E::kCorners> on_face{};
    for (int i : faces[f])
      if (i < E::kCorners) on_face[i] = true;
    for (int k = 0; k < static_cast<int>(maps.size()); ++k)
      for (int g = 0; g < E::kFaces; ++g) {
        bool inside = true;
        for (int i : faces[g]) {
          const Vec<E::kDim> xi = maps[k].offset + maps[k].scale * ref.row(i).transpose();
          const auto w = E::Linear::values(xi);
          for (int c = 0; c < E::kCorners; ++c) inside = inside && (on_face[c] || std::abs(w[c]) < 1e-12);
        }
        if (inside) out[f].emplace_back(k, g);
      }
  }
  return out;
}

/// New elements, nodes and the keys of all nodes (parent nodes first, with their ids kept).
template <class E>
std::vector<Key> refine_elements(const Mesh<E::kDim>& m, const std::vector<ChildMap<E::kDim>>& maps,
                                 Mesh<E::kDim>& out) {
  const auto ref = E::reference_nodes();
  std::map<Key, Index> ids;
  std::vector<Key> keys(m.nodes.size());
  for (Index e = 0; e < m.element_count(); ++e) {
    const auto nodes = m.element_nodes(e);
    for (int i = 0; i < E::kNodes; ++i) {
      Key key = corner_key<E>(nodes, ref.row(i).transpose());
      ids.emplace(key, nodes[i]);
      keys[nodes[i]] = std::move(key);
    }
  }
  out.nodes = m.nodes;
  for (Index e = 0; e < m.element_count(); ++e) {
    const auto nodes = m.element_nodes(e);
    const auto x = element_coordinates<E>(m, m.nodes, e);
    for (const auto& map : maps)
      for (int i = 0; i < E::kNodes; ++i) {
        const Vec<E::kDim> xi = map.offset + map.scale * ref.row(i).transpose();
        Key key = corner_key<E>(nodes, xi);
        const auto [it, inserted] = ids.emplace(key, out.node_count());
        if (inserted) {
          out.nodes.push_back(x.transpose() * E::values(xi));  // parent's isoparametric map
          keys.push_back(std::move(key));
        }
        out.connectivity.push_back(it->second);
      }
  }
  return keys;
}

/// Node set carried over: from the refined boundary faces of the same name where they exist, else
/// every new node whose key's corners all belong to the parent set.
template <class E>
std::vector<Index> refine_node_set(const Mesh<E::kDim>& m, const Mesh<E::kDim>& out, const std::string& name,
                                   const std::vector<Key>& keys) {
  std::vector<Index> set;
  const auto faces_it = out.boundary_faces.find(name);
  if (faces_it != out.boundary_faces.end()) {
    const auto faces = E::faces();
    for (const auto& [e, f] : faces_it->second)
      for (int i : faces[f]) set.push_back(out.element_nodes(e)[i]);
  } else {
    const auto& parent = m.node_sets.at(name);
    auto in_parent = [&](Index n) { return std::binary_search(parent.begin(), parent.end(), n); };
    set = parent;
    for (Index n = m.node_count(); n < out.node_count(); ++n) {
      bool all = true;
      for (const auto& [corner, w] : keys[n]) all = all && in_parent(corner);
      if (all) set.push_back(n);
    }
  }
  std::sort(set.begin(), set.end());
  set.erase(std::unique(set.begin(), set.end()), set.end());
  return set;
}

template <class E>
Mesh<E::kDim> refine_once(const Mesh<E::kDim>& m) {
  if (m.nodes_per_element != E::kNodes)
    throw std::invalid_argument(std::string("refine: ") + E::kName + " mesh with " +
                                std::to_string(m.nodes_per_element) + " nodes per element");
  const auto maps = child_maps<E>();
  const Index children = static_cast<Index>(maps.size());
  Mesh<E::kDim> out;
  out.shape = m.shape;
  out.nodes_per_element = E::kNodes;
  const std::vector<Key> keys = refine_elements<E>(m, maps, out);
  const auto table = child_faces<E>(maps);
  for (const auto& [name, faces] : m.boundary_faces) {
    auto& fine = out.boundary_faces[name];
    for (const auto& [e, f] : faces)
      for (const auto& [k, g] : table[f]) fine.emplace_back(e * children + k, g);
  }
  for (const auto& [name, elements] : m.element_sets) {
    auto& fine = out.element_sets[name];
    for (Index e : elements)
      for (Index k = 0; k < children; ++k) fine.push_back(e * children + k);
  }
  for (const auto& entry : m.node_sets)
    out.node_sets[entry.first] = refine_node_set<E>(m, out, entry.first, keys);
  return out;
}

}  // namespace

template <int D>
Mesh<D> refine(const Mesh<D>& mesh, int levels) {
  if (levels < 0) throw std::invalid_argument("refine: levels must be >= 0, got " + std::to_string(levels));
  Mesh<D> current = mesh;
  for (int level = 0; level < levels; ++level)
    current = visit_element_type_of_dim<D>(current.shape, [&](auto element) -> Mesh<D> {
      using E = decltype(element);
      if constexpr (E::kShape == ElementShape::BSpline2)  // no Lagrange nodes to split between
        throw std::invalid_argument(
            "refine: a B-spline patch is refined by its cell counts (structured_bspline2)");
      else
        return refine_once<E>(current);
    });
  return current;
}

template Mesh<2> refine(const Mesh<2>&, int);
template Mesh<3> refine(const Mesh<3>&, int);

}  // namespace matpoint::mesh
