// Gmsh .msh import (gmsh_import.hpp).
#include "matpoint/mesh/gmsh_import.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unordered_map>

#include "matpoint/core/errors.hpp"
#include "matpoint/mesh/gmsh_session.hpp"

namespace matpoint::mesh {

namespace {

/// The InputError for a problem with the mesh file.
[[noreturn]] void fail(const std::string& json_path, const std::string& file, const std::string& problem,
                       const std::string& expected) {
  throw InputError({InputIssue{json_path, "\"" + file + "\" (" + problem + ")", expected}});
}

/// Our shape of a Gmsh element type; false for types we do not read.
bool shape_of_gmsh_type(int type, ElementShape& shape) {
  switch (type) {
    case 2:
      shape = ElementShape::T3;
      return true;
    case 9:
      shape = ElementShape::T6;
      return true;
    case 3:
      shape = ElementShape::Q4;
      return true;
    case 10:
      shape = ElementShape::Q9;
      return true;
    case 5:
      shape = ElementShape::Hex8;
      return true;
    default:
      return false;
  }
}

std::string gmsh_type_name(GmshSession& gmsh, int type) {
  return gmsh.element_properties(type).name + " (Gmsh type " + std::to_string(type) + ")";
}

/// Gmsh's error messages ("Error: ...") in its log, joined by "; ".
std::string gmsh_errors(const std::vector<std::string>& log) {
  std::string out;
  const std::string prefix = "Error: ";
  for (const auto& line : log)
    if (line.rfind(prefix, 0) == 0) out += (out.empty() ? "" : "; ") + line.substr(prefix.size());
  return out;
}

/// Checks that `file` exists, is readable and starts like a .msh file (formats 2 and 4, ASCII or
/// binary, begin with "$MeshFormat"): Gmsh would run any other text as a .geo script, and reports a
/// missing file only on its silenced terminal.
void check_msh_file(const std::string& file, const std::string& json_path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail(json_path, file, "no such file", "a Gmsh .msh file");
  std::ifstream in(file, std::ios::binary);
  if (!in.good()) fail(json_path, file, "not readable", "a readable Gmsh .msh file");
  std::string head(11, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  if (head != "$MeshFormat")
    fail(json_path, file, "not a Gmsh mesh: it does not begin with $MeshFormat",
         "a Gmsh .msh file (format 2 or 4)");
}

/// Opens the file in Gmsh; Gmsh reports a corrupt file in its log (gmsh_session.hpp: errors do not
/// throw).
void open_in_gmsh(GmshSession& gmsh, const std::string& file, const std::string& json_path) {
  check_msh_file(file, json_path);
  gmsh.clear();
  gmsh.start_log();
  gmsh.open(file);
  const std::string errors = gmsh_errors(gmsh.stop_log());
  if (!errors.empty()) {
    gmsh.clear();
    fail(json_path, file, "Gmsh could not read it: " + errors, "a valid Gmsh .msh file (format 2 or 4)");
  }
}

/// Local-node permutation from Gmsh's order to ours (identity for the supported types, checked
/// against Gmsh's reference coordinates of the nodes).
template <class E>
std::array<int, E::kNodes> gmsh_to_local(GmshSession& gmsh, int type) {
  const GmshElementProperties p = gmsh.element_properties(type);
  const auto ref = E::reference_nodes();
  std::array<int, E::kNodes> perm{};
  for (int i = 0; i < E::kNodes; ++i) {
    perm[i] = -1;
    for (int j = 0; j < p.nodes; ++j) {
      bool same = true;
      for (int a = 0; a < E::kDim; ++a)
        same = same && std::abs(p.reference[j * p.dim + a] - ref(i, a)) < 1e-12;
      if (same) perm[i] = j;
    }
    if (perm[i] < 0) throw std::logic_error("gmsh import: no Gmsh node for a local node of " + p.name);
  }
  return perm;
}

/// Mirror image permutation (xi <-> eta swapped): turns a clockwise element counter-clockwise.
template <class E>
std::array<int, E::kNodes> mirror() {
  const auto ref = E::reference_nodes();
  std::array<int, E::kNodes> perm{};
  for (int i = 0; i < E::kNodes; ++i)
    for (int j = 0; j < E::kNodes; ++j)
      if (ref(j, 0) == ref(i, 1) && ref(j, 1) == ref(i, 0) &&
          (E::kDim == 2 || ref(j, E::kDim - 1) == ref(i, E::kDim - 1)))
        perm[i] = j;
  return perm;
}

/// The single element type of dimension D, its element tags and node tags.
template <int D>
GmshElementBlock elements_of_dimension(GmshSession& gmsh, const std::string& file,
                                       const std::string& json_path) {
  std::vector<GmshElementBlock> blocks = gmsh.elements(D);
  if (blocks.empty())
    fail(json_path, file, "no elements of dimension " + std::to_string(D),
         "a " + std::to_string(D) + "-D mesh");
  if (blocks.size() > 1) {
    std::string list;
    for (const auto& b : blocks) list += (list.empty() ? "" : ", ") + gmsh_type_name(gmsh, b.type);
    fail(json_path, file, "mixed element types: " + list, "one element type per mesh");
  }
  ElementShape shape{};
  if (!shape_of_gmsh_type(blocks[0].type, shape) || shape_dimension(shape) != D)
    fail(json_path, file, "unsupported element " + gmsh_type_name(gmsh, blocks[0].type),
         D == 2 ? "3-node or 6-node triangles, 4-node or 9-node quadrangles" : "8-node hexahedra");
  return std::move(blocks[0]);
}

/// Nodes of the D-dimensional elements, renumbered 0..n-1 in ascending tag order.
template <int D>
std::unordered_map<std::size_t, Index> read_nodes(GmshSession& gmsh, const GmshElementBlock& elements,
                                                  Mesh<D>& mesh) {
  std::vector<std::size_t> tags, all_tags;
  std::vector<double> coords;
  gmsh.nodes(all_tags, coords);
  std::unordered_map<std::size_t, std::size_t> where;
  for (std::size_t k = 0; k < all_tags.size(); ++k) where[all_tags[k]] = k;
  tags = elements.nodes;
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  std::unordered_map<std::size_t, Index> id;
  for (std::size_t tag : tags) {
    const std::size_t k = where.at(tag);
    id[tag] = mesh.node_count();
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = coords[3 * k + a];
    mesh.nodes.push_back(x);
  }
  return id;
}

/// Connectivity in our local order, each element counter-clockwise (positive Jacobian).
template <class E>
void read_connectivity(GmshSession& gmsh, const GmshElementBlock& elements,
                       const std::unordered_map<std::size_t, Index>& id, Mesh<E::kDim>& mesh) {
  const auto perm = gmsh_to_local<E>(gmsh, elements.type);
  const auto flip = mirror<E>();
  for (std::size_t e = 0; e < elements.tags.size(); ++e) {
    std::array<Index, E::kNodes> local{};
    for (int i = 0; i < E::kNodes; ++i) local[i] = id.at(elements.nodes[e * E::kNodes + perm[i]]);
    Eigen::Matrix<double, E::kNodes, E::kDim> x;
    for (int i = 0; i < E::kNodes; ++i) x.row(i) = mesh.nodes[local[i]].transpose();
    const bool clockwise = (x.transpose() * E::gradients(E::centre())).determinant() < 0.0;
    for (int i = 0; i < E::kNodes; ++i) mesh.connectivity.push_back(local[clockwise ? flip[i] : i]);
  }
}

/// Name of a physical group (its tag when unnamed).
std::string group_name(GmshSession& gmsh, int dim, int tag) {
  const std::string name = gmsh.physical_name(dim, tag);
  return name.empty() ? std::to_string(tag) : name;
}

/// Element tags of the physical group (dim, tag): the elements of all its entities.
std::vector<std::size_t> group_elements(GmshSession& gmsh, int dim, int tag,
                                        std::vector<std::size_t>& node_tags) {
  std::vector<std::size_t> out;
  for (int entity : gmsh.physical_group_entities(dim, tag))
    for (const auto& block : gmsh.elements(dim, entity)) {
      out.insert(out.end(), block.tags.begin(), block.tags.end());
      node_tags.insert(node_tags.end(), block.nodes.begin(), block.nodes.end());
    }
  return out;
}

/// Faces of the mesh by their sorted corner nodes -> (element, local face).
template <class E>
std::map<std::vector<Index>, std::pair<Index, int>> face_index(const Mesh<E::kDim>& mesh) {
  std::map<std::vector<Index>, std::pair<Index, int>> index;
  const auto faces = E::faces();
  for (Index e = 0; e < mesh.element_count(); ++e)
    for (int f = 0; f < E::kFaces; ++f) {
      std::vector<Index> corners;
      for (int i : faces[f])
        if (i < E::kCorners) corners.push_back(mesh.element_nodes(e)[i]);
      std::sort(corners.begin(), corners.end());
      index.emplace(corners, std::make_pair(e, f));
    }
  return index;
}

/// Physical groups of dimension D - 1: node sets (all their nodes) and boundary faces (matched to
/// element faces by their corner nodes, the first corners of each Gmsh face element).
template <class E>
void read_boundary_groups(GmshSession& gmsh, const std::unordered_map<std::size_t, Index>& id,
                          Mesh<E::kDim>& mesh) {
  constexpr int D = E::kDim;
  constexpr int kFaceCorners = E::kSimplex ? D : (D == 2 ? 2 : 4);
  const auto index = face_index<E>(mesh);
  for (const auto& [dim, tag] : gmsh.physical_groups(D - 1)) {
    std::vector<std::size_t> node_tags;
    const auto elements = group_elements(gmsh, dim, tag, node_tags);
    const std::string name = group_name(gmsh, dim, tag);
    auto& set = mesh.node_sets[name];
    for (std::size_t n : node_tags)
      if (id.count(n) != 0) set.push_back(id.at(n));
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    auto& faces = mesh.boundary_faces[name];
    const std::size_t per = elements.empty() ? 0 : node_tags.size() / elements.size();
    for (std::size_t k = 0; k < elements.size(); ++k) {
      std::vector<Index> corners;
      for (int c = 0; c < kFaceCorners; ++c)
        if (id.count(node_tags[k * per + c]) != 0) corners.push_back(id.at(node_tags[k * per + c]));
      std::sort(corners.begin(), corners.end());
      const auto it = index.find(corners);
      if (it != index.end()) faces.push_back(it->second);
    }
    std::sort(faces.begin(), faces.end());
  }
}

/// Physical groups of dimension D: element sets (our element ids, ascending).
template <int D>
void read_element_groups(GmshSession& gmsh, const GmshElementBlock& elements, Mesh<D>& mesh) {
  std::unordered_map<std::size_t, Index> element_id;
  for (std::size_t e = 0; e < elements.tags.size(); ++e) element_id[elements.tags[e]] = static_cast<Index>(e);
  for (const auto& [dim, tag] : gmsh.physical_groups(D)) {
    std::vector<std::size_t> node_tags;
    auto& set = mesh.element_sets[group_name(gmsh, dim, tag)];
    for (std::size_t t : group_elements(gmsh, dim, tag, node_tags)) set.push_back(element_id.at(t));
    std::sort(set.begin(), set.end());
  }
}

template <class E>
Mesh<E::kDim> build_mesh(GmshSession& gmsh, const GmshElementBlock& elements) {
  Mesh<E::kDim> mesh;
  mesh.shape = E::kShape;
  mesh.nodes_per_element = E::kNodes;
  const auto id = read_nodes<E::kDim>(gmsh, elements, mesh);
  read_connectivity<E>(gmsh, elements, id, mesh);
  read_element_groups<E::kDim>(gmsh, elements, mesh);
  read_boundary_groups<E>(gmsh, id, mesh);
  return mesh;
}

}  // namespace

template <int D>
Mesh<D> read_gmsh(const std::string& file, const std::string& json_path) {
  GmshSession gmsh;
  open_in_gmsh(gmsh, file, json_path);
  try {
    const GmshElementBlock elements = elements_of_dimension<D>(gmsh, file, json_path);
    ElementShape shape{};
    shape_of_gmsh_type(elements.type, shape);
    Mesh<D> mesh = visit_element_type_of_dim<D>(shape, [&](auto e) -> Mesh<D> {
      if constexpr (decltype(e)::kShape == ElementShape::BSpline2)  // Gmsh has no B-spline cells
        throw std::logic_error("read_gmsh: a Gmsh element type read as a B-spline cell");
      else
        return build_mesh<decltype(e)>(gmsh, elements);
    });
    gmsh.clear();
    return mesh;
  } catch (const std::out_of_range&) {  // a node or element tag that the file does not define
    gmsh.clear();
    fail(json_path, file, "an element refers to a node or element tag the file does not define",
         "a consistent Gmsh .msh file");
  } catch (...) {
    gmsh.clear();
    throw;
  }
}

template Mesh<2> read_gmsh(const std::string&, const std::string&);
template Mesh<3> read_gmsh(const std::string&, const std::string&);

}  // namespace matpoint::mesh
