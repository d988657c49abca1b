// The input reader, section heat: coupled heat conduction in the explicit solver (Nairn 2026
// §3.2.2, §3.5; docs/theory/heat.md) (docs/input.md).
#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"

namespace matpoint::input_detail {

void SpecReader::read_heat(const Value& v) {
  check_material_heat(v.present());
  if (!v.present()) return;
  const Object h(v,
                 {"initial_temperature", "conduction", "thermoelastic", "friction", "transfer", "fmpm_order",
                  "temperature_sine", "conditions", "contact", "contact_conductance", "body_temperatures"});
  if (!h.valid()) return;
  HeatSpec& out = spec_.heat;
  out.enabled = true;
  set_if(out.initial_temperature, h.optional("initial_temperature").number(kPositive));
  set_if(out.conduction, h.optional("conduction").boolean());
  set_if(out.thermoelastic, h.optional("thermoelastic").boolean());
  set_if(out.friction, h.optional("friction").boolean());
  set_if(out.transfer, h.optional("transfer").choice(kHeatTransfers));
  const Value order = h.optional("fmpm_order");
  if (order.present() && out.transfer != HeatTransfer::FMPM)
    order.fail("no fmpm_order unless transfer is \"fmpm\"");
  else
    set_if(out.fmpm_order, order.integer(1, 100));
  read_heat_sine(Object(h.optional("temperature_sine"), {"amplitude", "wave_vector", "phase"}));
  read_thermal_conditions(h.optional("conditions"));
  read_thermal_contact(h);
  read_body_temperatures(h.optional("body_temperatures"));
  if (spec_.solver.is_implicit())
    v.fail("no \"heat\" section with an implicit solver.type (explicit runs only)");
}

/// {"amplitude": A, "wave_vector": k, "phase": phi}: T = T0 + A sin(k . x + phi).
void SpecReader::read_heat_sine(const Object& s) {
  if (!s.valid()) return;
  HeatSpec& out = spec_.heat;
  out.has_sine = true;
  set_if(out.sine_amplitude, s.required("amplitude").number());
  set_if(out.sine_wave_vector, s.required("wave_vector").vector(dim_));
  set_if(out.sine_phase, s.optional("phase").number());
}

/// [{"face": "x-", "temperature": T} or {"face": "x+", "flux": q}, ...]
void SpecReader::read_thermal_conditions(const Value& list) {
  for (const auto& item : list.elements("an array of {\"face\", \"temperature\" or \"flux\"}")) {
    const Object c(item, {"face", "temperature", "flux"});
    if (!c.valid()) continue;
    ThermalConditionSpec out;
    const Value face = c.required("face");
    const auto id = face.choice(kFaces);
    if (!id) continue;
    out.face_axis = *id / 2;
    out.face_side = *id % 2;
    if (dim_ != 0 && out.face_axis >= dim_) {
      face.fail(faces_text());
      continue;
    }
    const bool temperature = c.has("temperature"), flux = c.has("flux");
    if (temperature == flux) {
      c.value().fail(
          "exactly one of \"temperature\" (a number > 0) and \"flux\" (a number: heat into the "
          "domain per unit face area)");
      continue;
    }
    out.kind = temperature ? ThermalConditionKind::Temperature : ThermalConditionKind::Flux;
    const auto value =
        temperature ? c.optional("temperature").number(kPositive) : c.optional("flux").number();
    if (!value) continue;
    out.value = *value;
    spec_.heat.conditions.push_back(out);
  }
}

/// "contact": "perfect" (default) | "conductance" (with "contact_conductance": h_c > 0) | "insulated",
/// only with a "contact" section: without one every body shares one velocity field and one
/// temperature field, so nothing is between bodies and the key would be ignored.
void SpecReader::read_thermal_contact(const Object& h) {
  HeatSpec& out = spec_.heat;
  const Value mode = h.optional("contact");
  set_if(out.contact, mode.choice(kThermalContacts));
  if (mode.present() && !contact_given_)
    mode.fail(
        "no heat.contact without a \"contact\" section (without contact the bodies share one temperature "
        "field and conduct as one body; add \"contact\" or remove heat.contact)");
  const Value conductance = h.optional("contact_conductance");
  if (out.contact == ThermalContact::Conductance)
    set_if(out.contact_conductance, h.required("contact_conductance").number(kPositive));
  else if (conductance.present())
    conductance.fail("no contact_conductance unless contact is \"conductance\"");
}

/// [{"body": name, "temperature": T}, ...]: initial temperatures in place of initial_temperature,
/// each body at most once (a second entry would silently override the first).
void SpecReader::read_body_temperatures(const Value& list) {
  std::vector<std::string> names;
  for (const auto& b : spec_.bodies) names.push_back(b.name);
  std::vector<std::size_t> given(names.size(), 0);  // 1 + the entry that set each body
  std::size_t index = 0;
  for (const auto& item : list.elements("an array of {\"body\": name, \"temperature\": T}")) {
    const std::size_t entry = index++;
    const Object b(item, {"body", "temperature"});
    if (!b.valid()) continue;
    const Value body = b.required("body");
    const auto name = body.string();
    const auto it = name ? std::find(names.begin(), names.end(), *name) : names.end();
    if (it == names.end()) {
      body.fail("the name of a body: " + join(names, true));
      continue;
    }
    auto& first = given[static_cast<std::size_t>(it - names.begin())];
    if (first != 0) {
      body.fail("each body at most once (\"" + *name + "\" is already at heat.body_temperatures[" +
                std::to_string(first - 1) + "])");
      continue;
    }
    first = entry + 1;
    const auto T = b.required("temperature").number(kPositive);
    if (T) spec_.heat.body_temperatures.emplace_back(static_cast<int>(it - names.begin()), *T);
  }
}

void SpecReader::check_material_heat(bool heat) const {
  for (std::size_t i = 0; i < spec_.materials.size(); ++i) {
    const MaterialSpec& m = spec_.materials[i];
    const std::string path = "materials[" + std::to_string(i) + "].";
    if (heat && m.model != MaterialModel::Rigid && !(m.heat_capacity > 0.0))
      issues_.add(path + "heat_capacity", "missing",
                  "a number > 0 (C_V, J/(kg K)) for every deformable material when the input has a \"heat\" "
                  "section");
    if (!heat)
      for (const auto& [key, value] :
           {std::pair{"heat_capacity", m.heat_capacity}, std::pair{"conductivity", m.conductivity},
            std::pair{"thermal_expansion", m.thermal_expansion}})
        if (value != 0.0)
          issues_.add(
              path + key, format_number(value),
              std::string("no ") + key + " without a \"heat\" section (coupled heat conduction is off)");
  }
}

}  // namespace matpoint::input_detail
