// The input reader, section mesh (implicit runs; docs/input.md): a structured mesh (Q4, Q9, T3,
// Hex8) or a Gmsh file.
// The run's `grid` (particle seeding and the inside-the-domain checks of bodies) is the mesh's
// bounding box with the mean element size of the refined mesh.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"
#include "matpoint/mesh/gmsh_import.hpp"

namespace matpoint::input_detail {

namespace {

constexpr int kMaxRefine = 8;  // 4^8 = 65 536 elements per coarse element in 2-D

template <int D>
void mesh_bounding_box(const mesh::Mesh<D>& m, Triple& lo, Triple& hi) {
  for (int a = 0; a < D; ++a) {
    lo[a] = kInf, hi[a] = -kInf;
    for (const auto& x : m.nodes) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
  }
}

}  // namespace

void SpecReader::read_mesh(const Object& m) {
  const std::size_t issues_before = issues_.size();
  MeshSpec& out = spec_.mesh;
  out.enabled = true;
  if (m.has("file")) {
    read_mesh_file(m);
  } else {
    const auto element = m.required("element").choice(kMeshElements);
    if (!element) return;
    out.element = *element;
    dim_ = out.element == MeshElement::Hex8 ? 3 : 2;
    read_mesh_diagonal(m);
    if (m.has("lines")) {
      read_mesh_lines(m);
    } else {
      const auto lo = m.required("min").vector(dim_);
      const auto hi = m.required("max").vector(dim_);
      const Value cells = m.required("cells");
      const auto counts = cells.vector(dim_, {1, 1e6, false, false});
      set_if(out.ratio, m.optional("ratio").vector(dim_, kPositive));
      if (!lo || !hi || !counts) return;
      out.min = *lo, out.max = *hi;
      for (int a = 0; a < dim_; ++a) {
        out.cells[static_cast<std::size_t>(a)] = static_cast<int>((*counts)[a]);
        if ((*counts)[a] != std::floor((*counts)[a]))
          cells.fail("an array of " + std::to_string(dim_) + " whole numbers >= 1");
        if (!(out.max[a] > out.min[a]))
          m.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each greater than mesh.min's");
      }
    }
  }
  set_if(out.refine, m.optional("refine").integer(0, kMaxRefine));
  if (out.element == MeshElement::BSpline2) {
    if (m.has("lines"))
      m.optional("lines").fail("no lines with mesh.element \"bspline2\" (a B-spline patch has equal cells)");
    for (int a = 0; a < dim_; ++a)
      if (out.ratio[a] != 1.0)
        m.optional("ratio").fail(
            numbers_text(dim_, kAnyNumber) +
            ", each 1, with mesh.element \"bspline2\" (a B-spline patch has equal cells)");
  }
  if (issues_.size() != issues_before) return;
  GridSpec& g = spec_.grid;
  g.dim = dim_;
  g.min = out.min, g.max = out.max;
  const double split = std::ldexp(1.0, out.refine);
  for (int a = 0; a < dim_; ++a) {
    const auto k = static_cast<std::size_t>(a);
    g.cells[k] = static_cast<int>(out.cells[k] * split);
    g.cell_size[a] = (g.max[a] - g.min[a]) / g.cells[k];
  }
  grid_ok_ = true;
}

/// mesh.lines: the coarse mesh's lines along each axis, [[x0, x1, ...], [y0, ...]] (each at least two
/// increasing numbers), instead of min, max, cells and ratio: layers of any sizes (Aulisa &
/// Capodaglio's Test C: an FE plate of two 0.8 m layers under the graded background grid).
void SpecReader::read_mesh_lines(const Object& m) {
  MeshSpec& out = spec_.mesh;
  for (const char* key : {"min", "max", "cells", "ratio"})
    if (m.has(key))
      m.optional(key).fail(std::string("no ") + key + " with mesh.lines (the lines give the mesh)");
  const Value lines = m.optional("lines");
  const auto axes =
      lines.elements("an array of " + std::to_string(dim_) + " arrays of increasing coordinates", 1);
  if (axes.empty()) return;
  if (axes.size() != static_cast<std::size_t>(dim_)) {
    lines.fail("an array of " + std::to_string(dim_) + " arrays (one per axis) of increasing coordinates");
    return;
  }
  for (int a = 0; a < dim_; ++a) {
    const Value& axis = axes[static_cast<std::size_t>(a)];
    std::vector<double> values;
    bool ok = true;
    for (const Value& x : axis.elements("at least two increasing numbers", 2)) {
      const auto v = x.number();
      if (!v)
        ok = false;
      else
        values.push_back(*v);
    }
    if (values.size() < 2 || !ok) continue;
    if (!std::is_sorted(values.begin(), values.end(), std::less_equal<>())) {
      axis.fail("at least two increasing numbers (strictly)");
      continue;
    }
    out.min[a] = values.front(), out.max[a] = values.back();
    out.cells[static_cast<std::size_t>(a)] = static_cast<int>(values.size()) - 1;
    out.lines[static_cast<std::size_t>(a)] = std::move(values);
  }
}

/// mesh.diagonal: how a structured T3 mesh splits its cells (mesh/triangle_pattern.hpp); only
/// with element "t3". The default, "alternating", prefers neither diagonal direction
/// (examples/implicit-rolling-disk-incline/README.md: what a single direction does to a rolling disk).
void SpecReader::read_mesh_diagonal(const Object& m) {
  MeshSpec& out = spec_.mesh;
  out.diagonal = mesh::TrianglePattern::Alternating;
  if (!m.has("diagonal")) return;
  if (out.element != MeshElement::T3) {
    m.optional("diagonal")
        .fail("no diagonal unless mesh.element is \"t3\" (it splits the cells into triangles)");
    return;
  }
  set_if(out.diagonal, m.optional("diagonal").choice(kTrianglePatterns));
}

/// mesh.file: read here already, so that a missing or broken file is an input error (exit 2)
/// naming the file; its dimension decides the run's.
void SpecReader::read_mesh_file(const Object& m) {
  MeshSpec& out = spec_.mesh;
  out.element = MeshElement::FromFile;
  const auto file = m.required("file").string();
  const auto dim = m.required("dim").integer(2, 3);
  for (const char* key : {"element", "min", "max", "cells", "ratio", "lines", "diagonal"})
    if (m.has(key))
      m.optional(key).fail(std::string("no ") + key + " with mesh.file (the file gives the mesh)");
  if (!file || !dim) return;
  dim_ = static_cast<int>(*dim);
  out.file = *file;
  try {
    Triple lo{}, hi{};
    std::size_t elements = 0;
    if (dim_ == 2) {
      const auto mesh = mesh::read_gmsh<2>(out.file, m.required("file").path());
      mesh_bounding_box(mesh, lo, hi), elements = static_cast<std::size_t>(mesh.element_count());
    } else {
      const auto mesh = mesh::read_gmsh<3>(out.file, m.required("file").path());
      mesh_bounding_box(mesh, lo, hi), elements = static_cast<std::size_t>(mesh.element_count());
    }
    out.min = lo, out.max = hi;
    // A Gmsh mesh has no cell counts: the mean element size per axis from the element count.
    const double per_axis = std::pow(static_cast<double>(elements), 1.0 / dim_);
    for (int a = 0; a < dim_; ++a)
      out.cells[static_cast<std::size_t>(a)] = std::max(1, static_cast<int>(per_axis));
  } catch (const InputError& error) {
    for (const auto& issue : error.issues()) issues_.add(issue.path, issue.value, issue.expected);
  }
}

}  // namespace matpoint::input_detail
