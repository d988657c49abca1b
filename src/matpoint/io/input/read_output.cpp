// The input reader, section output, probes, checkpoints and checks (docs/input.md).
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

void SpecReader::read_output(const Object& o) {
  OutputSpec& out = spec_.output;
  set_if(out.every_steps, o.optional("every_steps").integer(0));
  set_if(out.every_time, o.optional("every_time").number(kNonNegative));
  if (out.every_steps != 0 && out.every_time != 0)
    o.optional("every_time").fail("0 when every_steps is nonzero (one of every_steps or every_time)");
  set_if(out.particles, o.optional("particles").boolean());
  set_if(out.plots, o.optional("plots").boolean());
  std::vector<std::string_view> field_names;
  for (const auto& f : kParticleFields) field_names.push_back(f.name);
  const std::string fields_text = "one of the particle fields " + join(field_names, true);
  for (const auto& item : o.optional("fields").elements("an array of particle field names")) {
    const auto name = item.string();
    if (!name) continue;
    if (is_particle_field(*name))
      out.fields.push_back(*name);
    else
      item.fail(fields_text);
  }
  read_checkpoint_keys(Object(o.optional("checkpoint"), {"every_steps", "every_minutes"}));
  read_probes(o.optional("probes"), spec_.output.probes);
  const Value nodes = o.optional("node_probes");
  if (nodes.present() && !spec_.solver.is_implicit())
    nodes.fail(
        "no node_probes unless solver.type is implicit (an explicit grid keeps no nodal displacement)");
  else
    read_probes(nodes, spec_.output.node_probes);
}

/// output.probes (or node_probes): [{"name": "tip", "position": [x, y]}, ...] (docs/input.md#output).
void SpecReader::read_probes(const Value& list, std::vector<ProbeSpec>& out) {
  std::set<std::string> names;
  for (const auto& item : list.elements("an array of probe objects {\"name\", \"position\"}")) {
    const Object p(item, {"name", "position"});
    if (!p.valid()) continue;
    ProbeSpec probe;
    const Value name = p.required("name");
    if (const auto text = name.string()) {
      const bool plain = std::all_of(text->begin(), text->end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
      });
      if (!plain)
        name.fail("a name of letters, digits, '_' and '-' (it names history.csv columns)");
      else if (!names.insert(*text).second)
        name.fail("a name different from every other probe's");
      probe.name = *text;
    }
    const Value position = p.required("position");
    if (const auto x = position.vector(dim_)) {
      probe.position = *x;
      if (grid_ok_ && !box_inside_grid(*x, *x, 0.0))
        position.fail("a point inside the grid " + grid_box_text() + "; it " + overhang_text(*x, *x));
    }
    out.push_back(probe);
  }
}

/// output.checkpoint: every N steps and/or every T wall-clock minutes (docs/input.md#output).
void SpecReader::read_checkpoint_keys(const Object& c) {
  if (!c.valid()) return;
  CheckpointSpec& out = spec_.output.checkpoint;
  set_if(out.every_steps, c.optional("every_steps").integer(1));
  set_if(out.every_minutes, c.optional("every_minutes").number(kPositive));
  if (!c.has("every_steps") && !c.has("every_minutes"))
    c.value().fail("an object with every_steps (an integer >= 1) and/or every_minutes (a number > 0)");
}

void SpecReader::read_checks(const Value& list) {
  for (const auto& item : list.elements("an array of check objects")) {
    const Object c(item, {"name", "measure", "expected", "tolerance", "source", "kind"});
    if (!c.valid()) continue;
    CheckSpec check;
    set_if(check.name, c.required("name").string());
    read_measure(c.required("measure"), check);
    set_if(check.expected, c.required("expected").number());
    set_if(check.tolerance, c.required("tolerance").number(kNonNegative));
    set_if(check.source, c.required("source").string());
    set_if(check.kind, c.optional("kind").choice(kCheckKinds));
    spec_.checks.push_back(check);
  }
}

void SpecReader::read_measure(const Value& v, CheckSpec& check) {
  std::vector<std::string_view> names;
  for (const auto& m : kMeasures) names.push_back(m.name);
  const std::string expected = "one of the measures " + join(names, true);
  if (!v.usable(expected)) return;
  if (!v.get().is_string() || !is_known_measure(v.get().get_ref<const std::string&>())) {
    v.fail(expected);
    return;
  }
  check.measure = v.get().get<std::string>();
}

}  // namespace matpoint::input_detail
