// The .pvtu of a run on several MPI ranks (io/vtk_writer.hpp pvtu_file; docs/output.md "Runs on
// several MPI ranks"), read back with a small XML scan of its own: VTK's parallel unstructured grid
// format (docs.vtk.org, "XML File Formats", Parallel) is a VTKFile of type PUnstructuredGrid with a
// PUnstructuredGrid element (GhostLevel), PPointData / PCellData / PPoints holding one PDataArray
// per array of the pieces (same Name, type and NumberOfComponents as the pieces' DataArray
// elements; no data), and one Piece element per piece file (Source: its path relative to the
// .pvtu). Every piece must have the same arrays, whatever number of particles it holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "matpoint/io/vtk_writer.hpp"

namespace {

using namespace matpoint;

using Attributes = std::map<std::string, std::string>;

Attributes attributes_of(const std::string& element) {
  Attributes out;
  static const std::regex attribute(R"re(([A-Za-z_][A-Za-z0-9_]*)="([^"]*)")re");
  for (auto it = std::sregex_iterator(element.begin(), element.end(), attribute);
       it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = (*it)[2];
  return out;
}

/// The XML text before the appended binary data.
std::string head_of(const std::string& file) { return file.substr(0, file.find("<AppendedData")); }

/// The attributes of every `tag` element between <section> and </section> (the whole text for "").
std::vector<Attributes> elements(const std::string& text, const std::string& section,
                                 const std::string& tag) {
  std::string body = text;
  if (!section.empty()) {
    const auto begin = text.find("<" + section + ">");
    if (begin == std::string::npos) return {};
    const auto end = text.find("</" + section + ">", begin);
    body = text.substr(begin, end - begin);
  }
  std::vector<Attributes> out;
  const std::regex element("<" + tag + R"re(\s[^>]*>)re");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), element); it != std::sregex_iterator(); ++it)
    out.push_back(attributes_of(it->str()));
  return out;
}

/// What a reader needs to know of an array declaration: Name, type, NumberOfComponents and the
/// component names.
std::vector<Attributes> declared(std::vector<Attributes> arrays) {
  for (auto& a : arrays) {
    a.erase("format");
    a.erase("offset");
  }
  return arrays;
}

ParticleSet<2> particles(int count) {
  ParticleSet<2> ps;
  ps.state_stride = 2;
  ps.plastic_material = {1};
  ps.has_temperature = true;
  for (int k = 0; k < count; ++k)
    ps.add(Vec<2>(0.1 * k, 0.2), Vec<2>(1, -k), 2.0, 0.5, Vec<2>(0.1, 0.1), 0, k % 2);
  return ps;
}

TEST(Pvtu, DeclaresThePiecesArraysAndNamesEveryPiece) {
  const std::string piece = particles_vtu(particles(5), {}, true, {"eps_p", "yield"});
  const std::vector<std::string> files{"particles_000003_r0000.vtu", "particles_000003_r0001.vtu",
                                       "particles_000003_r0002.vtu"};
  const std::string pvtu = pvtu_file(piece, files);

  const auto root = elements(pvtu, "", "VTKFile");
  ASSERT_EQ(root.size(), 1u);
  EXPECT_EQ(root[0].at("type"), "PUnstructuredGrid");
  const auto grid = elements(pvtu, "", "PUnstructuredGrid");
  ASSERT_EQ(grid.size(), 1u);
  EXPECT_EQ(grid[0].at("GhostLevel"), "0");
  std::vector<std::string> sources;
  for (const auto& p : elements(pvtu, "", "Piece")) sources.push_back(p.at("Source"));
  EXPECT_EQ(sources, files);

  // PPointData: the piece's PointData arrays, in order, with the same attributes but no data
  const auto point_arrays = declared(elements(head_of(piece), "PointData", "DataArray"));
  ASSERT_FALSE(point_arrays.empty());
  EXPECT_EQ(elements(pvtu, "PPointData", "PDataArray"), point_arrays);
  std::vector<std::string> names;
  for (const auto& a : point_arrays) names.push_back(a.at("Name"));
  for (const char* expected : {"velocity", "displacement", "stress", "id", "state", "temperature"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  // PPoints: Points, Float64, 3 components, as the piece's
  const auto points = elements(pvtu, "PPoints", "PDataArray");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].at("Name"), "Points");
  EXPECT_EQ(points[0].at("type"), "Float64");
  EXPECT_EQ(points[0].at("NumberOfComponents"), "3");
  EXPECT_EQ(points, declared(elements(head_of(piece), "Points", "DataArray")));
  EXPECT_TRUE(elements(pvtu, "PCellData", "PDataArray").empty());  // particles have no cell data
  for (const auto& a : elements(pvtu, "", "PDataArray")) {
    EXPECT_EQ(a.count("offset"), 0u);
    EXPECT_EQ(a.count("format"), 0u);
  }
  // the state array's component names carry over
  for (const auto& a : elements(pvtu, "PPointData", "PDataArray"))
    if (a.at("Name") == "state") {
      EXPECT_EQ(a.at("NumberOfComponents"), "2");
      EXPECT_EQ(a.at("ComponentName0"), "eps_p");
      EXPECT_EQ(a.at("ComponentName1"), "yield");
    }
}

// A rank without particles writes a valid piece that declares the same arrays (temperature and
// state included), so the .pvtu is the same whichever rank's piece it is made from.
TEST(Pvtu, APieceWithoutParticlesDeclaresTheSameArrays) {
  const std::string full = particles_vtu(particles(4), {}, true, {"a", "b"});
  const std::string empty = particles_vtu(particles(0), {}, true, {"a", "b"});
  EXPECT_NE(head_of(empty).find("NumberOfPoints=\"0\""), std::string::npos);
  EXPECT_EQ(declared(elements(head_of(empty), "PointData", "DataArray")),
            declared(elements(head_of(full), "PointData", "DataArray")));
  EXPECT_EQ(pvtu_file(empty, {"x_r0000.vtu", "x_r0001.vtu"}),
            pvtu_file(full, {"x_r0000.vtu", "x_r0001.vtu"}));
}

TEST(Pvtu, DomainsDeclareTheirCellData) {
  const auto ps = particles(3);
  std::vector<ParticleSet<2>::Corners> corners(3);
  for (std::size_t p = 0; p < 3; ++p)
    for (int k = 0; k < 4; ++k)
      corners[p][static_cast<std::size_t>(k)] = ps.x[p] + Vec<2>(0.05 * (k & 1), 0.05 * (k >> 1));
  const std::string piece = domains_vtu<2>(corners, ps);
  const std::string pvtu = pvtu_file(piece, {"domains_000000_r0000.vtu"});
  const auto cell_arrays = elements(pvtu, "PCellData", "PDataArray");
  ASSERT_EQ(cell_arrays.size(), 2u);
  EXPECT_EQ(cell_arrays, declared(elements(head_of(piece), "CellData", "DataArray")));
  EXPECT_EQ(cell_arrays[0].at("Name"), "id");
  EXPECT_EQ(cell_arrays[0].at("type"), "Int64");
  EXPECT_EQ(cell_arrays[1].at("Name"), "body");
  EXPECT_EQ(cell_arrays[1].at("type"), "Int32");
  EXPECT_TRUE(elements(pvtu, "PPointData", "PDataArray").empty());
}

TEST(Pvtu, RefusesTextThatIsNotAnUnstructuredGrid) {
  EXPECT_THROW((void)pvtu_file("<VTKFile type=\"PolyData\">", {"a.vtu"}), std::invalid_argument);
}

}  // namespace
