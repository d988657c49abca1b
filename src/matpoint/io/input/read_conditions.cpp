// The input reader, section boundary conditions (docs/input.md).
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

void SpecReader::read_conditions(const Value& list) {
  for (const auto& item : list.elements("an array of boundary condition objects")) {
    const bool wall = item.get().is_object() && item.get().value("type", json()) == "moving_wall";
    if (spec_.mesh.enabled)
      spec_.conditions.push_back(read_mesh_condition(
          Object(item, {"type", "boundary", "normal", "receding", "velocity", "one_sided"})));
    else if (wall)
      spec_.conditions.push_back(read_moving_wall(
          Object(item, {"type", "axis", "position", "material", "velocity", "depth", "stretch_about"})));
    else
      spec_.conditions.push_back(
          read_condition(Object(item, {"face", "box", "type", "normal", "velocity", "one_sided"})));
  }
}

/// {"type": "moving_wall", "axis", "position", "material": "below"|"above", "velocity", "depth",
///  "stretch_about"} (Nairn 2026 §3.1).
VelocityConditionSpec SpecReader::read_moving_wall(const Object& c) const {
  VelocityConditionSpec out;
  out.kind = ConditionKind::MovingWall;
  out.on_face = false;
  if (!c.valid()) return out;
  if (const auto axis = c.required("axis").choice(kAxes)) {
    out.normal_axis = *axis;
    if (dim_ != 0 && *axis >= dim_)
      c.required("axis").fail("an axis of the grid (" + std::to_string(dim_) + "-D)");
  }
  set_if(out.wall_position, c.required("position").number());
  set_if(out.material_below, c.required("material").choice(kMaterialSides));
  const std::string expected = "a number (a constant wall velocity) or {\"table\": [[t, v], ...]}";
  if (auto v = read_time_function(c.required("velocity"), expected)) out.wall_velocity = *v;
  set_if(out.depth, c.required("depth").number(kNonNegative));
  out.stretch_about = c.optional("stretch_about").number();
  return out;
}

void SpecReader::check_receding_mesh(const Value& v, double receding) const {
  if (receding > 0 && spec_.mesh.element != MeshElement::Q9 && spec_.mesh.element != MeshElement::FromFile)
    v.fail(
        "0 unless mesh.element is \"q9\" (the receding correction of eq. (47) needs three nodes along each "
        "line normal to a face)");
}

/// A condition of an implicit run: "fixed" (every component 0), "slip" (the normal component 0) or
/// "velocity" (the listed components move at the prescribed velocity) on the nodes of a named mesh boundary,
/// with the receding-contact constant C_c in [0, 1] of its faces (Aulisa & Capodaglio §5, eq. (47) as
/// corrected in extraction A3); "one_sided": a fixed or slip wall that only pushes
/// (implicit/one_sided_boundary.hpp).
VelocityConditionSpec SpecReader::read_mesh_condition(const Object& c) const {
  VelocityConditionSpec out;
  if (!c.valid()) return out;
  const Value type = c.required("type");
  const auto kind = type.choice(kConditionKinds);
  if (kind && *kind != ConditionKind::Fixed && *kind != ConditionKind::Slip &&
      *kind != ConditionKind::Velocity)
    type.fail("\"fixed\", \"slip\" or \"velocity\" (an implicit run's conditions act on mesh boundaries)");
  set_if(out.kind, kind);
  read_condition_velocity(c, out);
  if (const auto boundary = c.required("boundary").string()) {
    out.boundary = *boundary;
    check_mesh_boundary(c.required("boundary"), *boundary);
  }
  if (out.kind == ConditionKind::Slip) {
    const auto axis = c.required("normal").choice(kAxes);
    if (axis && *axis >= dim_)
      c.required("normal").fail("an axis of the mesh's " + std::to_string(dim_) + " dimensions");
    set_if(out.normal_axis, axis);
  } else if (c.has("normal")) {
    c.optional("normal").fail("no normal unless type is \"slip\"");
  }
  set_if(out.receding, c.optional("receding").number(kUnitInterval));
  check_receding_mesh(c.optional("receding"), out.receding);
  if (const auto one_sided = c.optional("one_sided").boolean(); one_sided && *one_sided) {
    if (out.kind == ConditionKind::Velocity)
      c.optional("one_sided")
          .fail("false: one_sided only on a \"fixed\" or \"slip\" boundary (a wall at rest)");
    out.one_sided = true;
    check_one_sided_normal(c, out);
  }
  if (out.kind == ConditionKind::Velocity && c.has("receding"))
    c.optional("receding")
        .fail("no receding on a \"velocity\" boundary (the correction is for walls at rest)");
  return out;
}

/// A one-sided slip wall on a side of the structured mesh holds the side's own normal component
/// (a Gmsh boundary's plane is checked at set-up, implicit_mpm_solver.hpp).
void SpecReader::check_one_sided_normal(const Object& c, const VelocityConditionSpec& out) const {
  const std::string& side = out.boundary;
  const bool known = side == "left" || side == "right" || side == "bottom" || side == "top" ||
                     side == "back" || side == "front";
  if (out.kind != ConditionKind::Slip || !spec_.mesh.file.empty() || !known || !c.has("normal")) return;
  const int axis = side == "left" || side == "right" ? 0 : side == "bottom" || side == "top" ? 1 : 2;
  if (out.normal_axis != axis)
    c.required("normal").fail(std::string("\"") + "xyz"[axis] +
                              "\", the side's normal (a one-sided slip wall holds its own normal component)");
}

void SpecReader::check_mesh_boundary(const Value& v, const std::string& name) const {
  if (!spec_.mesh.file.empty()) return;
  std::vector<std::string_view> sides{"left", "right", "bottom", "top"};
  if (dim_ == 3) sides.insert(sides.end(), {"back", "front"});
  if (std::find(sides.begin(), sides.end(), name) == sides.end())
    v.fail("a side of the structured mesh: one of " + join(sides, true));
}

VelocityConditionSpec SpecReader::read_condition(const Object& c) const {
  VelocityConditionSpec out;
  if (!c.valid()) return out;
  read_region(c, out);
  const auto kind = c.required("type").choice(kConditionKinds);
  set_if(out.kind, kind);
  if (!kind) return out;
  read_normal(c, *kind, out);
  read_condition_velocity(c, out);
  read_one_sided(c.optional("one_sided"), out);
  return out;
}

/// "velocity": required for type "velocity" (grid faces, boxes and mesh boundaries alike), refused otherwise.
void SpecReader::read_condition_velocity(const Object& c, VelocityConditionSpec& out) const {
  const Value velocity = c.optional("velocity");
  if (out.kind == ConditionKind::Velocity) {
    if (velocity.present())
      read_prescribed_velocity(velocity, out);
    else
      c.missing("velocity", prescribed_velocity_text());
  } else if (velocity.present()) {
    velocity.fail("no velocity unless type is \"velocity\"");
  }
}

/// "one_sided": true on a fixed or slip face (slip with the face's own normal), not with FMPM/XPIC.
void SpecReader::read_one_sided(const Value& v, VelocityConditionSpec& out) const {
  const auto one_sided = v.boolean();
  if (!one_sided || !*one_sided) return;
  const bool face_normal = out.kind == ConditionKind::Fixed || out.normal_axis == out.face_axis;
  if (!out.on_face || out.kind == ConditionKind::Velocity || !face_normal)
    v.fail("one_sided only on a \"fixed\" face or a \"slip\" face with the face's normal");
  else
    out.one_sided = true;
}

/// One-sided conditions decide per step which nodes they hold; the FMPM/XPIC increments would need
/// that choice cached, so they are refused there.
void SpecReader::check_one_sided_transfer(const Value& list) const {
  const auto t = spec_.solver.transfer;
  if (t != VelocityTransfer::FMPM && t != VelocityTransfer::XPIC) return;
  for (std::size_t i = 0; i < spec_.conditions.size(); ++i)
    if (spec_.conditions[i].one_sided)
      list.element(i)
          .member("one_sided", false)
          .fail("false (one_sided conditions need transfer flip, pic or blend)");
}

/// Exactly one of "face" and "box".
void SpecReader::read_region(const Object& c, VelocityConditionSpec& out) const {
  const bool face = c.has("face"), box = c.has("box");
  if (face && box) {
    c.optional("box").fail("no box when a face is given (exactly one of face or box)");
  } else if (face) {
    const Value v = c.optional("face");
    const auto id = v.choice(kFaces);
    if (!id) return;
    out.on_face = true;
    out.face_axis = *id / 2;
    out.face_side = *id % 2;
    if (dim_ != 0 && out.face_axis >= dim_) v.fail(faces_text());
  } else if (box) {
    out.on_face = false;
    const Object b(c.optional("box"), {"min", "max"});
    const auto lo = b.required("min").vector(dim_);
    const auto hi = b.required("max").vector(dim_);
    if (!lo || !hi) return;
    out.box_min = *lo;
    out.box_max = *hi;
    for (int a = 0; a < dim_; ++a)
      if (out.box_max[a] < out.box_min[a]) {
        b.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each at least the box min's");
        return;
      }
  } else {
    c.missing("face", "exactly one of \"face\" (" + faces_text() + ") or \"box\"");
  }
}

/// The faces of the grid's dimension, e.g. "one of "x-", "x+", "y-", "y+"".
std::string SpecReader::faces_text() const {
  std::vector<std::string_view> names;
  for (const auto& face : kFaces)
    if (dim_ == 0 || face.value / 2 < dim_) names.push_back(face.name);
  return "one of " + join(names, true);
}

void SpecReader::read_normal(const Object& c, ConditionKind kind, VelocityConditionSpec& out) const {
  const Value normal = c.optional("normal");
  if (kind != ConditionKind::Slip) {
    if (normal.present()) normal.fail("no normal unless type is \"slip\"");
    return;
  }
  out.normal_axis = out.face_axis;
  if (!normal.present()) {
    if (c.has("box") && !c.has("face"))
      c.missing("normal", "\"x\", \"y\" or \"z\": the constrained axis of a slip box");
    return;
  }
  const auto axis = normal.choice(kAxes);
  if (!axis) return;
  if (dim_ != 0 && *axis >= dim_) {
    std::vector<std::string_view> names;
    for (int a = 0; a < dim_; ++a) names.push_back(kAxes[static_cast<std::size_t>(a)].name);
    normal.fail("one of " + join(names, true) + " (an axis of the " + std::to_string(dim_) + "-D grid)");
    return;
  }
  out.normal_axis = *axis;
}

std::string SpecReader::prescribed_velocity_text() const {
  const std::string count = dim_ == 0 ? "1 to 3" : std::to_string(dim_);
  return "an array of " + count + " entries, each a number, null (free) or {\"table\": [[t, v], ...]}";
}

void SpecReader::read_prescribed_velocity(const Value& v, VelocityConditionSpec& out) const {
  const std::string expected = prescribed_velocity_text();
  const bool size_ok = v.get().is_array() && (dim_ == 0 ? !v.get().empty() && v.get().size() <= 3
                                                        : v.get().size() == static_cast<std::size_t>(dim_));
  if (!size_ok) {
    v.fail(expected);
    return;
  }
  bool any_prescribed = false;
  for (std::size_t a = 0; a < v.get().size(); ++a) {
    const Value component = v.element(a);
    if (component.get().is_null()) continue;
    any_prescribed = true;
    out.velocity[a] = read_time_function(component, expected);
  }
  if (!any_prescribed) v.fail(expected + ", at least one not null");
}

/// A number (a constant) or {"table": [[t0, v0], [t1, v1], ...]} with strictly increasing t.
std::optional<TimeFunction> SpecReader::read_time_function(const Value& v, const std::string& expected) {
  if (!v.usable(expected)) return std::nullopt;  // absent: an issue when required (fuzzer finding)
  if (v.get().is_number()) {
    const auto x = v.number();
    if (!x) return std::nullopt;
    return TimeFunction{{}, {*x}};
  }
  if (!v.get().is_object()) {
    v.fail(expected);
    return std::nullopt;
  }
  const Object t(v, {"table"});
  const auto rows = t.required("table").elements("an array of [t, v] rows, at least one", 1);
  TimeFunction out;
  for (const auto& row : rows) {
    const auto tv = row.vector(2);
    if (!tv) return std::nullopt;
    if (!out.times.empty() && !((*tv)[0] > out.times.back())) {
      row.fail("a row whose time is greater than the previous row's");
      return std::nullopt;
    }
    out.times.push_back((*tv)[0]);
    out.values.push_back((*tv)[1]);
  }
  if (rows.empty()) return std::nullopt;
  return out;
}

}  // namespace matpoint::input_detail
