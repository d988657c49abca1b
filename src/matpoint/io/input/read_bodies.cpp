// The input reader, section bodies (shapes, placement, initial state) (docs/input.md).
#include <algorithm>
#include <cassert>
#include <cctype>
#include <climits>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "matpoint/analysis/measures.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"
#include "matpoint/io/memory_estimate.hpp"
#include "matpoint/io/particle_fields.hpp"
#include "matpoint/shape/stencil_width.hpp"

namespace matpoint::input_detail {

void SpecReader::read_bodies(const Value& list, std::size_t minimum) {
  const auto items =
      list.elements(minimum > 0 ? "a non-empty array of body objects" : "an array of body objects", minimum);
  for (std::size_t i = 0; i < items.size(); ++i) spec_.bodies.push_back(read_body(items[i], i));
}

BodySpec SpecReader::read_body(const Value& v, std::size_t index) {
  const Object b(v, {"name", "material", "shape", "particles_per_cell", "placement", "velocity",
                     "velocity_sine", "velocity_gradient", "velocity_noise", "geostatic"});
  BodySpec out;
  out.name = "body" + std::to_string(index);
  if (!b.valid()) return out;
  set_if(out.name, b.optional("name").string());
  read_body_material(b.required("material"), out);
  read_shape(b.required("shape"), out);
  set_if(out.particles_per_cell, b.optional("particles_per_cell").integer(1, 10));
  read_placement(b, out);
  set_if(out.velocity, b.optional("velocity").vector(dim_));
  read_sine(Object(b.optional("velocity_sine"), {"amplitude", "wave_vector", "phase"}), out);
  read_velocity_gradient(b.optional("velocity_gradient"), out);
  const Object noise(b.optional("velocity_noise"), {"amplitude", "seed"});
  if (noise.valid()) {
    set_if(out.noise_amplitude, noise.required("amplitude").number(kNonNegative));
    if (const auto seed = noise.optional("seed").integer(0, UINT_MAX))
      out.noise_seed = static_cast<unsigned>(*seed);
  }
  read_geostatic(b.optional("geostatic"), out);
  return out;
}

/// placement: "uniform" (the default: particles at the centres of ppc^D equal sub-cells) or "gauss"
/// (at the 2 x 2 (x 2) or, with particles_per_cell 3, the 3 x 3 (x 3) Gauss points of each cell, each
/// with its weight's share of the cell's volume: a finite-element quadrature, 3 x 3 for Q9, as Iaconeta 2017 §4.1 places its material points; on a
/// structured T3 mesh at the 3 points of the degree-2 rule of each triangle, each with a third of
/// its area, Iaconeta 2017 §5.2's three material points per cell).
void SpecReader::read_placement(const Object& b, BodySpec& out) const {
  const Value placement = b.optional("placement");
  const auto text = placement.string();
  if (!text) return;
  if (*text != "uniform" && *text != "gauss") {
    placement.fail("\"uniform\" or \"gauss\"");
    return;
  }
  const MeshSpec& mesh = spec_.mesh;
  if (*text == "gauss" && mesh.enabled && mesh.element == MeshElement::T3) {
    read_triangle_placement(b, out);
    return;
  }
  out.gauss_points = *text == "gauss";
  if (out.gauss_points && out.particles_per_cell != 2 && out.particles_per_cell != 3)
    placement.fail("\"uniform\" unless particles_per_cell is 2 or 3 (\"gauss\" places the 2- or 3-point "
                   "Gauss-Legendre rule per direction)");
  if (out.gauss_points && (out.shape == BodyShape::GradedDisk || out.shape == BodyShape::GradedBeam))
    placement.fail("\"uniform\" (a graded body places its own particles)");
}

/// placement "gauss" on a structured T3 mesh: three particles per triangle, in the triangles of the
/// grid cells split as mesh.diagonal splits them (particles/generators.cpp), so the cells must be
/// the run's grid cells (no grading).
void SpecReader::read_triangle_placement(const Object& b, BodySpec& out) const {
  const Value placement = b.optional("placement");
  if (b.has("particles_per_cell")) {
    b.optional("particles_per_cell")
        .fail("no particles_per_cell with placement \"gauss\" on a \"t3\" mesh (3 per triangle)");
    return;
  }
  for (int a = 0; a < dim_; ++a)
    if (spec_.mesh.ratio[a] != 1.0) {
      placement.fail(
          "\"uniform\" on a graded mesh (\"gauss\" on a \"t3\" mesh needs mesh.ratio 1: its "
          "triangles must be halves of equal cells)");
      return;
    }
  if (out.shape == BodyShape::GradedDisk || out.shape == BodyShape::GradedBeam) {
    placement.fail("\"uniform\" (a graded body places its own particles)");
    return;
  }
  out.triangle_points = spec_.mesh.diagonal;
}

/// {"k0": K0 >= 0, "surface": height of the free surface}: an initial geostatic stress, held by
/// a plastic material's history (the elastic models' stress is a function of F alone).
void SpecReader::read_geostatic(const Value& v, BodySpec& out) const {
  const Object g(v, {"k0", "surface"});
  if (!v.present() || !g.valid()) return;
  out.geostatic = true;
  set_if(out.k0, g.required("k0").number(kNonNegative));
  set_if(out.geostatic_surface, g.required("surface").number());
  if (!names_complete_ || static_cast<std::size_t>(out.material) >= spec_.materials.size()) return;
  const MaterialModel model = spec_.materials[static_cast<std::size_t>(out.material)].model;
  if (model != MaterialModel::MohrCoulomb && model != MaterialModel::DruckerPrager &&
      model != MaterialModel::VonMises)
    v.fail("no geostatic stress for a " + std::string(name_of(kModels, model)) +
           " body (only mohr_coulomb, drucker_prager and von_mises materials hold an initial stress)");
}

void SpecReader::read_body_material(const Value& v, BodySpec& out) const {
  const auto name = v.string();
  if (!name || !names_complete_) return;  // an unnamed material is reported already
  for (std::size_t k = 0; k < spec_.materials.size(); ++k)
    if (spec_.materials[k].name == *name) {
      out.material = static_cast<int>(k);
      return;
    }
  std::vector<std::string> names;
  for (const auto& m : spec_.materials) names.push_back(m.name);
  v.fail("the name of a material: " + join(names, true));
}

void SpecReader::read_shape(const Value& v, BodySpec& out) const {
  if (!v.expect_object(
          "an object with \"type\": " +
          join(std::array{"box", "disk", "sphere", "polygon", "graded_disk", "graded_beam"}, true)))
    return;
  const std::size_t issues_before = issues_.size();
  const Value type = v.member("type", true);
  const auto kind = type.choice(kShapes);
  if (!kind) return;
  out.shape = *kind;
  switch (*kind) {
    case BodyShape::Box:
      read_box(Object(v, {"type", "min", "max"}), out);
      break;
    case BodyShape::Disk:  // "disk" in 1-D and 2-D (and, as before, in 3-D), "sphere" in 3-D
      if (dim_ != 0 && dim_ != 3 && type.get() == "sphere")
        type.fail("\"disk\" (\"sphere\" needs grid.dim 3)");
      else
        read_disk(Object(v, {"type", "center", "radius"}), out);
      break;
    case BodyShape::Polygon:
      if (dim_ != 0 && dim_ != 2 && dim_ != 3)
        type.fail("\"box\" or \"disk\" (a polygon needs grid.dim 2, or 3 with \"z\": a prism)");
      else if (dim_ == 3)
        read_prism(Object(v, {"type", "vertices", "z"}), out);
      else
        read_polygon(Object(v, {"type", "vertices"}), out);
      break;
    case BodyShape::GradedDisk:
      if (dim_ != 0 && dim_ != 2)
        type.fail("\"box\" or \"disk\" (a graded disk is 2-D)");
      else
        read_graded_disk(
            Object(v, {"type", "center", "radius", "core_radius", "core_divisions", "layer_growth"}), out);
      break;
    case BodyShape::GradedBeam:
      if (dim_ != 0 && dim_ != 2)
        type.fail("\"box\" or \"disk\" (a graded beam is 2-D)");
      else
        read_graded_beam(Object(v, {"type", "min", "max", "core_height", "core_rows", "layer_growth"}), out);
      break;
  }
  if (grid_ok_ && issues_.size() == issues_before) check_inside_grid(v, out);
}

void SpecReader::read_box(const Object& s, BodySpec& out) const {
  const auto lo = s.required("min").vector(dim_);
  const auto hi = s.required("max").vector(dim_);
  if (!lo || !hi) return;
  out.min = *lo;
  out.max = *hi;
  for (int a = 0; a < dim_; ++a)
    if (!(out.max[a] > out.min[a])) {
      s.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each greater than the box min's");
      return;
    }
}

/// Aulisa & Capodaglio's graded disk (Appendix A, the code's variant; extraction §10.1): R0 < R,
/// N_theta0 >= 7 (one core ring at least), f > 1 with (R - R0) / dR < 1 / (f - 1), dR = R0 / floor(N_theta0 /
/// 2 pi), so that a finite number of layers reaches R.
void SpecReader::read_graded_disk(const Object& s, BodySpec& out) const {
  read_disk(s, out);
  const auto core = s.required("core_radius").number(kPositive);
  const auto divisions = s.optional("core_divisions").integer(7, 100000);
  const auto growth = s.optional("layer_growth").number({1, 10, true, false});
  set_if(out.core_divisions, divisions);
  set_if(out.layer_growth, growth);
  if (!core || !(out.radius > 0)) return;
  out.core_radius = *core;
  if (!(*core < out.radius)) {
    s.required("core_radius").fail("a number > 0 and < radius");
    return;
  }
  const double ring_step = *core / std::floor(out.core_divisions / (2 * 3.141592653589793));
  const std::string expected =
      "a growth f > 1 small enough that layers of thickness dR / f^k reach radius: "
      "(radius - core_radius) / dR < 1 / (f - 1)";
  if ((out.radius - *core) / ring_step >= 1.0 / (out.layer_growth - 1.0)) {
    const Value growth = s.optional("layer_growth");
    if (growth.present())
      growth.fail(expected);
    else  // the default does not fit these radii: say so rather than "got missing"
      issues_.add(growth.path(), "missing (the default " + format_number(out.layer_growth) + ")",
                  expected + ": give one");
  }
}

/// Aulisa & Capodaglio's graded beam (Appendix A, the code's variant; extraction §10.2): the box
/// min/max is the beam, its left end the clamped one; a core of core_rows (N_H >= 2) rows over
/// core_height (H0, at most the height), boundary layers of ratio f > 1 on the top, right end and
/// bottom.
void SpecReader::read_graded_beam(const Object& s, BodySpec& out) const {
  read_box(s, out);
  const auto core = s.required("core_height").number(kPositive);
  set_if(out.core_divisions, s.required("core_rows").integer(2, 100000));
  set_if(out.layer_growth, s.optional("layer_growth").number({1, 10, false, false}));
  if (!core) return;
  out.core_height = *core;
  const double height = out.max[1] - out.min[1], length = out.max[0] - out.min[0];
  if (height > 0 && *core > height)
    s.required("core_height").fail("a number > 0 and at most the beam's height (box max y - min y)");
  else if (height > 0 && !(length > 0.5 * (height - *core)))
    s.required("max").fail("a beam longer than (height - core_height) / 2");
}

void SpecReader::read_disk(const Object& s, BodySpec& out) const {
  set_if(out.center, s.required("center").vector(dim_));
  set_if(out.radius, s.required("radius").number(kPositive));
}

void SpecReader::read_polygon(const Object& s, BodySpec& out) {
  const Value list = s.required("vertices");
  const auto items = list.elements("an array of at least 3 [x, y] points", 3);
  for (const auto& item : items) {
    const auto point = item.vector(2);
    if (!point) return;
    out.polygon.push_back({(*point)[0], (*point)[1]});
  }
  if (items.empty()) return;
  double twice_area = 0;  // shoelace formula
  for (std::size_t k = 0; k < out.polygon.size(); ++k) {
    const auto& p = out.polygon[k];
    const auto& q = out.polygon[(k + 1) % out.polygon.size()];
    twice_area += p[0] * q[1] - q[0] * p[1];
  }
  const auto [lo, hi] = bounding_box(out, 2);
  if (std::abs(twice_area) <= 1e-12 * (hi[0] - lo[0]) * (hi[1] - lo[1]))
    list.fail("the vertices of a polygon with nonzero area");
}

/// A 3-D polygon: the prism of the polygon `vertices` in x-y between z = `z`[0] and `z`[1] (held in
/// min[2], max[2]), e.g. a rod: a disk's polygon extruded along its axis (examples/taylor-bar).
void SpecReader::read_prism(const Object& s, BodySpec& out) {
  read_polygon(s, out);
  const Value z = s.required("z");
  const auto range = z.vector(2);
  if (!range) return;
  if (!((*range)[1] > (*range)[0])) {
    z.fail("[z_min, z_max] with z_max > z_min");
    return;
  }
  out.min[2] = (*range)[0];
  out.max[2] = (*range)[1];
}

std::pair<Triple, Triple> SpecReader::bounding_box(const BodySpec& body, int dim) {
  Triple lo{}, hi{};
  switch (body.shape) {
    case BodyShape::Box:
    case BodyShape::GradedBeam:
      return {body.min, body.max};
    case BodyShape::Disk:
    case BodyShape::GradedDisk:
      for (int a = 0; a < dim; ++a) {
        lo[a] = body.center[a] - body.radius;
        hi[a] = body.center[a] + body.radius;
      }
      return {lo, hi};
    case BodyShape::Polygon:
      lo = {kInf, kInf, 0};
      hi = {-kInf, -kInf, 0};
      for (const auto& p : body.polygon)
        for (int a = 0; a < 2; ++a) {
          lo[a] = std::min(lo[a], p[a]);
          hi[a] = std::max(hi[a], p[a]);
        }
      if (dim == 3) lo[2] = body.min[2], hi[2] = body.max[2];  // a prism
      return {lo, hi};
  }
  return {lo, hi};
}

void SpecReader::check_inside_grid(const Value& shape, const BodySpec& body) const {
  const auto [lo, hi] = bounding_box(body, dim_);
  if (!box_inside_grid(lo, hi, kInsideTolerance))
    shape.fail("a shape inside the grid " + grid_box_text() + "; it " + overhang_text(lo, hi));
}

/// "reaches 0.2 beyond the x+ side (x = 1.2 > grid.max[0] = 1)": each side the box [lo, hi] crosses.
std::string SpecReader::overhang_text(const Triple& lo, const Triple& hi) const {
  const GridSpec& g = spec_.grid;
  std::vector<std::string> sides;
  for (int a = 0; a < dim_; ++a) {
    const std::string axis(1, "xyz"[a]);
    std::string index = "[";  // appended: "[" + std::to_string(a) trips a GCC 12 -Wrestrict false positive
    index += std::to_string(a);
    index += ']';
    if (lo[a] < g.min[a])
      sides.push_back(format_number(g.min[a] - lo[a]) + " beyond the " + axis + "- side (" + axis + " = " +
                      format_number(lo[a]) + " < grid.min" + index + " = " + format_number(g.min[a]) + ")");
    if (hi[a] > g.max[a])
      sides.push_back(format_number(hi[a] - g.max[a]) + " beyond the " + axis + "+ side (" + axis + " = " +
                      format_number(hi[a]) + " > grid.max" + index + " = " + format_number(g.max[a]) + ")");
  }
  std::string out = "reaches ";
  for (std::size_t i = 0; i < sides.size(); ++i) out += (i == 0 ? "" : " and ") + sides[i];
  return out;
}

/// [lo, hi] lies in the grid's box, widened by `relative_tolerance` of its size.
bool SpecReader::box_inside_grid(const Triple& lo, const Triple& hi, double relative_tolerance) const {
  const GridSpec& g = spec_.grid;
  for (int a = 0; a < dim_; ++a) {
    const double tolerance = relative_tolerance * (g.max[a] - g.min[a]);
    if (lo[a] < g.min[a] - tolerance || hi[a] > g.max[a] + tolerance) return false;
  }
  return true;
}

std::string SpecReader::grid_box_text() const {
  return "[min, max] (grid.min = " + vector_text(spec_.grid.min) +
         ", grid.max = " + vector_text(spec_.grid.max) + ")";
}

std::string SpecReader::vector_text(const Triple& x) const {
  std::vector<std::string> parts;
  for (int a = 0; a < dim_; ++a) parts.push_back(format_number(x[a]));
  std::string text = "[";  // appended: "[" + join(...) trips a GCC 12 -Wrestrict false positive
  text += join(parts, false);
  text += ']';
  return text;
}

/// A dim x dim matrix as an array of rows: V += G x.
void SpecReader::read_velocity_gradient(const Value& v, BodySpec& out) const {
  if (!v.present()) return;
  const std::string expected =
      "an array of " + std::to_string(dim_) + " rows of " + numbers_text(dim_, kAnyNumber);
  const auto rows = v.elements(expected, 1);
  if (dim_ != 0 && rows.size() != static_cast<std::size_t>(dim_) && !rows.empty()) {
    v.fail(expected);
    return;
  }
  for (std::size_t r = 0; r < rows.size() && r < 3; ++r)
    if (const auto row = rows[r].vector(dim_)) out.velocity_gradient[r] = *row;
  out.has_velocity_gradient = true;
}

void SpecReader::read_sine(const Object& s, BodySpec& out) const {
  if (!s.valid()) return;
  out.has_sine_velocity = true;
  set_if(out.sine_amplitude, s.required("amplitude").vector(dim_));
  set_if(out.sine_wave_vector, s.required("wave_vector").vector(dim_));
  set_if(out.sine_phase, s.optional("phase").number());
}

}  // namespace matpoint::input_detail
