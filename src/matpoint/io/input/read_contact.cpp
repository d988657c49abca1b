// The input reader, section contact (Nairn 2026 §3.2; docs/theory/contact.md) (docs/input.md).
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

void SpecReader::read_contact(const Value& v) {
  const bool has_rigid = std::any_of(spec_.materials.begin(), spec_.materials.end(),
                                     [](const MaterialSpec& m) { return m.model == MaterialModel::Rigid; });
  if (!v.present()) {
    if (has_rigid)
      v.fail("a \"contact\" object (a rigid material moves its own velocity field, which needs contact)");
    return;
  }
  contact_given_ = true;
  const Object c(v, {"law", "friction", "normals", "separation", "fmpm_method", "fields", "pairs"});
  if (!c.valid()) return;
  ContactSpec& out = spec_.contact;
  out.enabled = true;
  set_if(out.by_material, c.optional("fields").choice(kContactFields));
  out.law = read_contact_law(c);
  set_if(out.normals, c.optional("normals").choice(kContactNormals));
  out.separation = c.optional("separation").number(kNonNegative);
  set_if(out.fmpm_method, c.optional("fmpm_method").choice(kContactFmpmMethods));
  const std::vector<std::string> names = field_names(out.by_material);
  if (names.size() < 2)
    c.value().fail(std::string("at least two ") + (out.by_material ? "materials" : "bodies") +
                   " for contact (one velocity field each); remove \"contact\" for a single body");
  read_contact_pairs(c.optional("pairs"), names, out);
  check_contact_solver(v);
}

/// "law" (default "stick") and "friction" (Coulomb only, required there).
ContactLawSpec SpecReader::read_contact_law(const Object& c) {
  ContactLawSpec law;
  set_if(law.law, c.optional("law").choice(kContactLaws));
  const Value friction = c.optional("friction");
  if (law.law == ContactLaw::Coulomb) {
    if (friction.present())
      set_if(law.friction, friction.number(kNonNegative));
    else
      c.missing("friction", "a number >= 0 (the Coulomb coefficient mu) with law \"coulomb\"");
  } else if (friction.present()) {
    friction.fail("no friction unless law is \"coulomb\"");
  }
  return law;
}

std::vector<std::string> SpecReader::field_names(bool by_material) const {
  std::vector<std::string> names;
  if (by_material)
    for (const auto& m : spec_.materials) names.push_back(m.name);
  else
    for (const auto& b : spec_.bodies) names.push_back(b.name);
  return names;
}

/// [{"between": [name, name], "law", "friction"}, ...]: the law of one pair of fields.
void SpecReader::read_contact_pairs(const Value& list, const std::vector<std::string>& names,
                                    ContactSpec& out) const {
  for (const auto& item : list.elements("an array of {\"between\": [name, name], \"law\", \"friction\"}")) {
    const Object p(item, {"between", "law", "friction"});
    if (!p.valid()) continue;
    ContactPairSpec pair;
    pair.law = read_contact_law(p);
    const Value between = p.required("between");
    const std::string expected = "two different names of " +
                                 std::string(out.by_material ? "materials" : "bodies") + ": " +
                                 join(names, true);
    const auto ends = between.elements(expected, 2);
    if (ends.empty()) continue;
    if (ends.size() != 2) {
      between.fail(expected);
      continue;
    }
    std::array<int, 2> index{-1, -1};
    for (int k = 0; k < 2; ++k) {
      const auto name = ends[k].string();
      const auto it = name ? std::find(names.begin(), names.end(), *name) : names.end();
      if (it == names.end()) {
        ends[k].fail(expected);
        continue;
      }
      index[k] = static_cast<int>(it - names.begin());
    }
    if (index[0] < 0 || index[1] < 0) continue;
    if (index[0] == index[1]) {
      between.fail(expected);
      continue;
    }
    pair.first = index[0];
    pair.second = index[1];
    out.pairs.push_back(pair);
  }
}

/// Contact runs on the explicit solver's per-increment FMPM path with fixed-domain bases.
void SpecReader::check_contact_solver(const Value& v) const {
  const SolverSpec& s = spec_.solver;
  if (s.is_implicit()) {
    v.fail(
        "no contact with an implicit solver.type (contact is a mesh boundary condition with \"receding\")");
    return;
  }
  if (dim_ == 1) v.fail("no contact in a 1-D grid (contact needs grid.dim 2 or 3)");
  if (s.transfer == VelocityTransfer::XPIC)
    v.fail("no contact with transfer \"xpic\" (use \"fmpm\" or \"flip\")");
  if (s.transfer == VelocityTransfer::FMPM && s.fmpm.recursion == FmpmRecursion::Binomial)
    v.fail("no contact with fmpm.recursion \"binomial\" (eq. 4 has no per-increment contact step)");
  if (s.shape == ShapeKind::CPDI2)
    v.fail("no contact with solver.basis \"cpdi2\" (tracked corners); use \"cpdi1\"");
  if (s.mapping != Mapping::MPM) v.fail("no contact with solver.mapping other than \"mpm\"");
}

}  // namespace matpoint::input_detail
