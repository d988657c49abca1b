// The input reader, section fe_bodies (implicit runs; docs/input.md): finite element bodies made of
// mesh elements, coupled monolithically to the MPM background grid (Aulisa & Capodaglio §4;
// fem/fe_body.hpp). Which elements exist is known only once the mesh is built: the solver's set-up
// checks that the named set or the region holds elements.
#include <array>
#include <string>

#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"

namespace matpoint::input_detail {

void SpecReader::read_fe_bodies(const Value& list) {
  if (!list.present()) return;
  if (!spec_.solver.is_implicit() || spec_.solver.kind == SolverKind::ImplicitUl) {
    list.fail("no fe_bodies unless solver.type is \"implicit_mpm\" (Aulisa & Capodaglio's coupling)");
    return;
  }
  if (spec_.mesh.element == MeshElement::BSpline2) {
    list.fail(
        "no fe_bodies on a mesh.element \"bspline2\" (FE bodies are Lagrange elements of the mesh: \"q4\", "
        "\"q9\", \"t3\", \"hex8\" or a mesh file)");
    return;
  }
  const auto items = list.elements("a non-empty array of FE body objects", 1);
  for (std::size_t k = 0; k < items.size(); ++k) {
    const Object b(items[k],
                   {"name", "material", "elements", "region", "gravity", "inertia", "interface_receding"});
    if (!b.valid()) continue;
    FeBodySpec out;
    out.name = "fe_body" + std::to_string(k);
    set_if(out.name, b.optional("name").string());
    read_fe_material(b.required("material"), out);
    const bool named = b.has("elements"), region = b.has("region");
    if (named == region)
      b.value().fail(
          "exactly one of \"elements\" (a mesh element set: a Gmsh physical group of dimension dim) and "
          "\"region\" ({\"min\": [...], \"max\": [...]}: the elements whose centre lies in the box)");
    if (named) set_if(out.elements, b.optional("elements").string());
    if (region) {
      const Object r(b.optional("region"), {"min", "max"});
      if (r.valid()) {
        set_if(out.region_min, r.required("min").vector(dim_));
        set_if(out.region_max, r.required("max").vector(dim_));
      }
    }
    set_if(out.gravity, b.optional("gravity").boolean());
    set_if(out.unit_inertia_density, b.optional("inertia").choice(kFeInertia));
    set_if(out.interface_receding, b.optional("interface_receding").number(kUnitInterval));
    check_receding_mesh(b.optional("interface_receding"), out.interface_receding);
    spec_.fe_bodies.push_back(out);
  }
}

/// An elastic material by name: the Gauss points of an FE body keep no plastic history.
void SpecReader::read_fe_material(const Value& v, FeBodySpec& out) const {
  BodySpec body;
  body.material = -1;
  read_body_material(v, body);
  if (body.material < 0) return;  // reported
  out.material = body.material;
  const MaterialModel model = spec_.materials[static_cast<std::size_t>(out.material)].model;
  if (model != MaterialModel::NeoHookean && model != MaterialModel::LinearElastic)
    v.fail(
        "the name of a \"neo_hookean\" or \"linear_elastic\" material (an FE body's Gauss points keep no "
        "plastic history)");
}

}  // namespace matpoint::input_detail
