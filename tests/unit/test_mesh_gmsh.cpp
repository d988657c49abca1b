// Gmsh .msh import (mesh/gmsh_import.hpp): meshes written by Gmsh itself (a 3 x 2 rectangle
// with 3 x 2 transfinite quadrangles of order 2 -> Q9, triangles of order 1 and 2 -> T3 / T6, a
// recombined extruded box -> Hex8) in formats 4 and 2, and a hand-written format-2 file with
// scattered node tags, an unused node and a clockwise element. Expected values are the geometry's:
// areas / volumes from the rectangle and box sizes, counts from the transfinite divisions.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "matpoint/core/errors.hpp"
#include "matpoint/mesh/gmsh_import.hpp"
#include "matpoint/mesh/gmsh_session.hpp"

/// LeakSanitizer (scripts/sanitize.sh): Gmsh 4.8 never frees a cache that its high-order meshing
/// (setOrder, used here to write Q9 and T6 meshes) fills, even in gmshFinalize; ours is not to fix.
extern "C" const char* __lsan_default_suppressions() { return "leak:libgmsh.so\n"; }

namespace {

using namespace matpoint;
using namespace matpoint::mesh;
namespace fs = std::filesystem;

/// This process's scratch folder, removed at exit.
fs::path temp_dir() {
  struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("matpoint_gmsh_" + std::to_string(::getpid()));
    ~Scratch() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  };
  static const Scratch scratch;
  fs::create_directories(scratch.dir);
  return scratch.dir;
}

struct RectangleOptions {
  bool recombine = true;
  int order = 2;
  double msh_version = 4.1;
  bool extrude = false;      // a 3-D box of 2 layers, recombined into hexahedra
  bool serendipity = false;  // 8-node quadrangles (not supported by the importer)
};

/// [0, 3] x [0, 2] with 3 x 2 transfinite cells, meshed by Gmsh from a .geo script; physical groups
/// "body" (surface, or volume of the box extruded to z = 1 in 2 layers), "bottom" (y = 0) and
/// "left" (x = 0), or for the box "base" (z = 0).
fs::path write_rectangle(const std::string& name, const RectangleOptions& o) {
  const fs::path geo = temp_dir() / (name + ".geo"), file = temp_dir() / name;
  std::ofstream script(geo);
  script << "Point(1) = {0, 0, 0}; Point(2) = {3, 0, 0}; Point(3) = {3, 2, 0}; Point(4) = {0, 2, 0};\n"
            "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
            "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
            "Transfinite Curve{1, 3} = 4; Transfinite Curve{2, 4} = 3; Transfinite Surface{1};\n";
  if (o.recombine) script << "Recombine Surface{1};\n";
  if (o.extrude) {
    script << "out[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };\n"
              "Physical Volume(\"body\") = {out[1]}; Physical Surface(\"base\") = {1};\n";
  } else {
    script << "Physical Surface(\"body\") = {1}; Physical Curve(\"bottom\") = {1}; Physical Curve(\"left\") "
              "= {4};\n";
  }
  script.close();
  GmshSession gmsh;
  gmsh.clear();
  gmsh.open(geo.string());
  gmsh.set_option("Mesh.MshFileVersion", o.msh_version);
  gmsh.set_option("Mesh.SecondOrderIncomplete", o.serendipity ? 1 : 0);
  gmsh.generate(o.extrude ? 3 : 2);
  gmsh.set_order(o.order);
  gmsh.write(file.string());
  gmsh.clear();
  return file;
}

/// Every node of the boundary faces of `name` and of node set `name` has coordinate `axis` = value.
template <int D>
void expect_side(const Mesh<D>& m, const std::string& name, int axis, double value, std::size_t faces,
                 std::size_t nodes) {
  EXPECT_EQ(m.boundary_faces.at(name).size(), faces) << name;
  EXPECT_EQ(m.node_sets.at(name).size(), nodes) << name;
  for (Index n : m.node_sets.at(name)) EXPECT_NEAR(m.nodes[n][axis], value, 1e-12);
  visit_element_type_of_dim<D>(m.shape, [&](auto element) {
    const auto local = decltype(element)::faces();
    for (const auto& [e, f] : m.boundary_faces.at(name))
      for (int i : local[f]) EXPECT_NEAR(m.nodes[m.element_nodes(e)[i]][axis], value, 1e-12);
  });
}

TEST(GmshImport, Q9RectangleInFormats4And2) {
  for (double version : {4.1, 2.2}) {
    const auto file = write_rectangle("q9_" + std::to_string(version) + ".msh", {.msh_version = version});
    const Mesh<2> m = read_gmsh<2>(file.string());
    EXPECT_EQ(m.shape, ElementShape::Q9);
    EXPECT_EQ(m.element_count(), 6);
    EXPECT_EQ(m.node_count(), 7 * 5);  // (2 * 3 + 1) x (2 * 2 + 1) lattice
    EXPECT_NEAR(mesh_measure<2>(m, m.nodes), 6.0, 1e-10);
    EXPECT_EQ(m.element_sets.at("body").size(), 6u);
    expect_side(m, "bottom", 1, 0.0, 3, 7);
    expect_side(m, "left", 0, 0.0, 2, 5);
    // Local order (Gmsh's = ours): each face's third node at the middle of its corners, node 8 at
    // the centre of the (rectangular) element.
    for (Index e = 0; e < m.element_count(); ++e) {
      const auto nodes = m.element_nodes(e);
      for (const auto& face : Q9::faces())
        EXPECT_LT(
            (m.nodes[nodes[face[2]]] - 0.5 * (m.nodes[nodes[face[0]]] + m.nodes[nodes[face[1]]])).norm(),
            1e-9);
      Vec<2> centre = Vec<2>::Zero();
      for (int c = 0; c < 4; ++c) centre += 0.25 * m.nodes[nodes[c]];
      EXPECT_LT((m.nodes[nodes[8]] - centre).norm(), 1e-9);
    }
  }
}

TEST(GmshImport, TrianglesOfOrderOneAndTwo) {
  for (int order : {1, 2}) {
    const auto file = write_rectangle(order == 1 ? "t3.msh" : "t6.msh", {.recombine = false, .order = order});
    const Mesh<2> m = read_gmsh<2>(file.string());
    EXPECT_EQ(m.shape, order == 1 ? ElementShape::T3 : ElementShape::T6);
    EXPECT_EQ(m.element_count(), 12);  // each transfinite cell split in two
    EXPECT_EQ(m.node_count(),
              order == 1 ? 4 * 3 : 7 * 5);  // T6: the diagonals' mid-nodes are the cell centres
    EXPECT_NEAR(mesh_measure<2>(m, m.nodes), 6.0, 1e-10);
    expect_side(m, "bottom", 1, 0.0, 3, order == 1 ? 4 : 7);
  }
}

TEST(GmshImport, Hex8Box) {
  const auto file = write_rectangle("hex.msh", {.order = 1, .extrude = true});
  const Mesh<3> m = read_gmsh<3>(file.string());
  EXPECT_EQ(m.shape, ElementShape::Hex8);
  EXPECT_EQ(m.element_count(), 3 * 2 * 2);
  EXPECT_EQ(m.node_count(), 4 * 3 * 3);
  EXPECT_NEAR(mesh_measure<3>(m, m.nodes), 6.0, 1e-10);
  expect_side(m, "base", 2, 0.0, 6, 12);
  EXPECT_EQ(m.element_sets.at("body").size(), 12u);
}

TEST(GmshImport, ScatteredTagsUnusedNodesAndClockwiseElements) {
  const fs::path file = temp_dir() / "scattered.msh";
  std::ofstream(file) << R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "body"
$EndPhysicalNames
$Nodes
7
101 0 0 0
205 1 0 0
307 2 0 0
409 0 1 0
511 1 1 0
613 2 1 0
999 5 5 0
$EndNodes
$Elements
4
1 1 2 1 1 101 205
2 1 2 1 1 205 307
7 3 2 2 1 101 205 511 409
9 3 2 2 1 205 511 613 307
$EndElements
)";
  const Mesh<2> m = read_gmsh<2>(file.string());
  EXPECT_EQ(m.node_count(), 6);  // node 999 belongs to no element
  EXPECT_EQ(m.element_count(), 2);
  EXPECT_EQ(m.nodes[0], Vec<2>(0, 0));  // ascending tags: 101 -> 0, ..., 613 -> 5
  EXPECT_EQ(m.nodes[5], Vec<2>(2, 1));
  EXPECT_NEAR(mesh_measure<2>(m, m.nodes), 2.0, 1e-14);  // element 9 turned counter-clockwise
  expect_side(m, "bottom", 1, 0.0, 2, 3);
  EXPECT_EQ(m.element_sets.at("body"), (std::vector<Index>{0, 1}));
}

/// The InputError's message from reading `file` in dimension D.
template <int D>
std::string import_error(const std::string& file) {
  try {
    read_gmsh<D>(file, "bodies[0].mesh");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GmshImport, ErrorsNameTheFileAndTheProblem) {
  const fs::path dir = temp_dir();
  const std::string missing = (dir / "missing.msh").string();
  EXPECT_NE(import_error<2>(missing).find("bodies[0].mesh: got \"" + missing + "\" (no such file)"),
            std::string::npos)
      << import_error<2>(missing);
  // Truncated: half of a valid file.
  const auto good = write_rectangle("good.msh", {});
  std::ifstream in(good);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string truncated = (dir / "truncated.msh").string();
  std::ofstream(truncated) << text.substr(0, text.size() / 2);
  const std::string message = import_error<2>(truncated);
  EXPECT_NE(message.find(truncated), std::string::npos) << message;
  EXPECT_NE(message.find("Gmsh could not read it"), std::string::npos) << message;
  // Not a mesh at all (Gmsh would run it as a .geo script), a header without elements, and a 2-D
  // mesh read as 3-D.
  const std::string garbage = (dir / "garbage.msh").string();
  std::ofstream(garbage) << "hello\n";
  EXPECT_NE(import_error<2>(garbage).find("does not begin with $MeshFormat"), std::string::npos)
      << import_error<2>(garbage);
  const std::string empty = (dir / "empty.msh").string();
  std::ofstream(empty) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  EXPECT_NE(import_error<2>(empty).find("no elements of dimension 2"), std::string::npos)
      << import_error<2>(empty);
  EXPECT_NE(import_error<3>(good.string()).find("no elements of dimension 3"), std::string::npos);
  // 8-node (serendipity) quadrangles.
  const auto q8 = write_rectangle("q8.msh", {.serendipity = true});
  const std::string unsupported = import_error<2>(q8.string());
  EXPECT_NE(unsupported.find("unsupported element Quadrilateral 8"), std::string::npos) << unsupported;
  EXPECT_NE(unsupported.find(q8.string()), std::string::npos);
}

TEST(GmshImport, MixedElementTypesAreRefused) {
  const fs::path file = temp_dir() / "mixed.msh";
  std::ofstream(file) << R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 2 0 0
$EndNodes
$Elements
2
1 3 2 1 1 1 2 3 4
2 2 2 1 1 2 5 3
$EndElements
)";
  const std::string message = import_error<2>(file.string());
  EXPECT_NE(message.find("mixed element types"), std::string::npos) << message;
  EXPECT_NE(message.find(file.string()), std::string::npos);
}

}  // namespace
