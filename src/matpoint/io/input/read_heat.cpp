// The input reader, section heat: coupled heat conduction in the explicit solver (Nairn 2026
// §3.2.2, §3.5; docs/theory/heat.md) (docs/input.md).
#include <array>
#include <string>
#include <utility>

#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"

namespace matpoint::input_detail {

void SpecReader::read_heat(const Value& v) {
  check_material_heat(v.present());
  if (!v.present()) return;
  const Object h(v, {"initial_temperature", "conduction", "thermoelastic", "friction", "transfer",
                     "fmpm_order", "temperature_sine", "conditions"});
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
