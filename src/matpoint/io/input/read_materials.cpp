// The input reader, section materials (docs/input.md).
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

void SpecReader::read_materials(const Value& list) {
  const auto items = list.elements("a non-empty array of material objects", 1);
  names_complete_ = !items.empty();
  for (const auto& item : items) spec_.materials.push_back(read_material(item));
}

MaterialSpec SpecReader::read_material(const Value& v) {
  const Object m(v, {"name",
                     "model",
                     "density",
                     "E",
                     "nu",
                     "lambda",
                     "mu",
                     "volumetric",
                     "bulk_sound_speed",
                     "hugoniot_slope",
                     "gruneisen",
                     "shear_modulus",
                     "velocity",
                     "cohesion",
                     "friction_angle",
                     "dilation_angle",
                     "softening",
                     "tension_cutoff",
                     "match",
                     "yield_stress",
                     "hardening_modulus",
                     "johnson_cook",
                     "heat_capacity",
                     "conductivity",
                     "thermal_expansion"});
  MaterialSpec out;
  if (!m.valid()) {
    names_complete_ = false;
    return out;
  }
  read_material_name(m.required("name"), out);
  const auto model = m.required("model").choice(kModels);
  set_if(out.model, model);
  set_if(out.density, m.required("density").number(kPositive));
  read_thermal(m, model, out);
  if (model) read_plasticity(m, *model, out);
  if (model == MaterialModel::MieGruneisen) return read_mie_gruneisen(m, out);
  if (model == MaterialModel::Rigid) {
    read_rigid(m, out);
    return out;
  }
  for (const char* key : {"bulk_sound_speed", "hugoniot_slope", "gruneisen", "shear_modulus"})
    if (m.has(key)) m.optional(key).fail(std::string("no \"") + key + "\" unless model is \"mie_gruneisen\"");
  if (m.has("velocity")) m.optional("velocity").fail("no velocity unless model is \"rigid\"");
  read_elasticity(m, out);
  const Value volumetric = m.optional("volumetric");
  if (model && model != MaterialModel::NeoHookean && volumetric.present())
    volumetric.fail("no \"volumetric\" key for a " + std::string(name_of(kModels, *model)) +
                    " material (only neo_hookean has one)");
  else
    set_if(out.volumetric, volumetric.choice(kVolumetric));
  return out;
}

/// The plastic models' keys (material/mohr_coulomb.hpp, drucker_prager.hpp, von_mises.hpp);
/// refuses them on the other models. Angles in degrees.
void SpecReader::read_plasticity(const Object& m, MaterialModel model, MaterialSpec& out) {
  const bool frictional = model == MaterialModel::MohrCoulomb || model == MaterialModel::DruckerPrager;
  const bool metal = model == MaterialModel::VonMises;
  for (const char* key : {"cohesion", "friction_angle", "dilation_angle", "softening"})
    if (!frictional && m.has(key))
      m.optional(key).fail(std::string("no \"") + key +
                           "\" unless model is \"mohr_coulomb\" or \"drucker_prager\"");
  if (model != MaterialModel::MohrCoulomb && m.has("tension_cutoff"))
    m.optional("tension_cutoff").fail("no \"tension_cutoff\" unless model is \"mohr_coulomb\"");
  if (model != MaterialModel::DruckerPrager && m.has("match"))
    m.optional("match").fail("no \"match\" unless model is \"drucker_prager\"");
  for (const char* key : {"yield_stress", "hardening_modulus", "johnson_cook"})
    if (!metal && m.has(key))
      m.optional(key).fail(std::string("no \"") + key + "\" unless model is \"von_mises\"");
  if (frictional) read_friction(m, out);
  if (model == MaterialModel::MohrCoulomb && m.has("tension_cutoff")) read_tension_cutoff(m, out);
  if (model == MaterialModel::DruckerPrager)
    set_if(out.match, m.optional("match").choice(kDruckerPragerMatches));
  if (metal) {
    set_if(out.yield_stress, m.required("yield_stress").number(kPositive));
    // H < 0 would make the yield stress sigma_y + H eps_p negative at eps_p = sigma_y / |H|.
    set_if(out.hardening_modulus, m.optional("hardening_modulus").number(kNonNegative));
    if (m.has("johnson_cook"))
      read_johnson_cook(Object(m.optional("johnson_cook"), {"B", "n", "C", "reference_rate"}), out);
  }
}

/// Mohr-Coulomb strength: c >= 0, 0 <= phi < 90 deg (phi = 0: Tresca, then c > 0), 0 <= psi <= phi,
/// optional linear softening {"cohesion": c_r, "friction_angle": phi_r, "plastic_strain": eps_s}
/// with c_r <= c, psi <= phi_r <= phi.
void SpecReader::read_friction(const Object& m, MaterialSpec& out) {
  set_if(out.cohesion, m.required("cohesion").number(kNonNegative));
  const auto phi = m.required("friction_angle").number({0, 90, false, true});
  set_if(out.friction_angle, phi);
  if (phi && *phi == 0.0 && out.cohesion == 0.0)
    m.required("cohesion").fail("c > 0 when friction_angle is 0 (Tresca: no strength otherwise)");
  const Value psi_value = m.optional("dilation_angle");
  const auto psi = psi_value.number(phi ? Bounds{0, *phi, false, false} : kNonNegative);
  set_if(out.dilation_angle, psi);
  out.residual_cohesion = out.cohesion;
  out.residual_friction_angle = out.friction_angle;
  const Object soft(m.optional("softening"), {"cohesion", "friction_angle", "plastic_strain"});
  if (!m.has("softening") || !soft.valid()) return;
  set_if(out.residual_cohesion, soft.required("cohesion").number({0, out.cohesion, false, false}));
  set_if(out.residual_friction_angle,
         soft.required("friction_angle")
             .number({std::max(out.dilation_angle, 0.0), out.friction_angle,
                      out.dilation_angle == 0.0 && out.friction_angle > 0.0, false}));
  set_if(out.softening_strain, soft.required("plastic_strain").number(kPositive));
}

/// von_mises "johnson_cook": {"B" >= 0, "n" > 0 (default 1), "C" >= 0 (default 0), "reference_rate" > 0
/// (default 1)}: sigma_f = (sigma_y + H eps_p + B eps_p^n)(1 + C ln(max(rate / reference_rate, 1))).
void SpecReader::read_johnson_cook(const Object& jc, MaterialSpec& out) {
  if (!jc.valid()) return;
  set_if(out.jc_b, jc.required("B").number(kNonNegative));
  set_if(out.jc_n, jc.optional("n").number(kPositive));
  set_if(out.jc_c, jc.optional("C").number(kNonNegative));
  set_if(out.jc_reference_rate, jc.optional("reference_rate").number(kPositive));
}

/// Mohr-Coulomb's tension cut-off sigma_t: 0 <= sigma_t < c cot(phi) (at the apex or above it the
/// cut-off would never act).
void SpecReader::read_tension_cutoff(const Object& m, MaterialSpec& out) {
  const double apex = out.friction_angle > 0
                          ? out.cohesion / std::tan(out.friction_angle * 3.14159265358979323846 / 180)
                          : std::numeric_limits<double>::infinity();  // Tresca: no apex
  std::ostringstream bound;
  bound << "a stress in [0, c cot(phi)) = [0, " << apex
        << ") (the apex of the Mohr-Coulomb pyramid; a cut-off at or "
        << "above it never acts)";
  const Value v = m.optional("tension_cutoff");
  const auto sigma_t = v.number(kNonNegative);
  if (!sigma_t) return;
  if (!(*sigma_t < apex)) {
    v.fail(bound.str());
    return;
  }
  out.tension_cutoff = *sigma_t;
}

/// model "mie_gruneisen" (material/mie_gruneisen.hpp): C0, S, Gamma0 and an optional shear modulus.
MaterialSpec SpecReader::read_mie_gruneisen(const Object& m, MaterialSpec& out) {
  for (const char* key : {"E", "nu", "lambda", "mu", "volumetric"})
    if (m.has(key)) m.optional(key).fail(std::string("no \"") + key + "\" for a mie_gruneisen material");
  set_if(out.bulk_sound_speed, m.required("bulk_sound_speed").number(kPositive));
  set_if(out.hugoniot_slope, m.required("hugoniot_slope").number(kNonNegative));
  set_if(out.gruneisen, m.required("gruneisen").number(kNonNegative));
  set_if(out.mu, m.optional("shear_modulus").number(kNonNegative));
  // lambda + 2 mu / 3 = K = rho0 C0^2, so that lambda + 2 mu is the dilatational modulus
  out.lambda = out.density * out.bulk_sound_speed * out.bulk_sound_speed - 2.0 * out.mu / 3.0;
  return out;
}

/// A rigid material: only name, model, density and an optional prescribed velocity (one entry
/// per axis, each a number or {"table": [[t, v], ...]}; zero by default).
void SpecReader::read_rigid(const Object& m, MaterialSpec& out) const {
  for (const char* key : {"E", "nu", "lambda", "mu", "volumetric"})
    if (m.has(key)) m.optional(key).fail("no elastic constants for a rigid material");
  const Value v = m.optional("velocity");
  if (!v.present()) return;
  const std::string expected = "an array of " + std::string(dim_ == 0 ? "1 to 3" : std::to_string(dim_)) +
                               " entries, each a number or {\"table\": [[t, v], ...]}";
  const bool size_ok = v.get().is_array() && (dim_ == 0 ? !v.get().empty() && v.get().size() <= 3
                                                        : v.get().size() == static_cast<std::size_t>(dim_));
  if (!size_ok) {
    v.fail(expected);
    return;
  }
  for (std::size_t a = 0; a < v.get().size(); ++a)
    if (auto f = read_time_function(v.element(a), expected)) out.rigid_velocity[a] = *f;
}

void SpecReader::read_material_name(const Value& v, MaterialSpec& out) {
  const auto name = v.string();
  if (!name) {
    names_complete_ = false;
    return;
  }
  for (const auto& other : spec_.materials)
    if (other.name == *name) {
      v.fail("a name not used by another material");
      return;
    }
  out.name = *name;
}

/// Exactly one pair: E and nu, or lambda and mu; the other pair is computed from it.
void SpecReader::read_elasticity(const Object& m, MaterialSpec& out) {
  const bool young = m.has("E") || m.has("nu");
  const bool lame = m.has("lambda") || m.has("mu");
  if (young && lame)
    m.optional(m.has("lambda") ? "lambda" : "mu")
        .fail("either E and nu, or lambda and mu, not keys of both pairs");
  else if (young)
    read_young(m, out);
  else if (lame)
    read_lame(m, out);
  else
    m.missing("E", "E and nu, or lambda and mu");
}

void SpecReader::read_young(const Object& m, MaterialSpec& out) {
  const auto E = m.required("E").number(kPositive);
  const auto nu = m.required("nu").number({-1, 0.5, true, true});
  if (!E || !nu) return;
  out.youngs_modulus = *E;
  out.poisson_ratio = *nu;
  out.lambda = *E * *nu / ((1 + *nu) * (1 - 2 * *nu));
  out.mu = *E / (2 * (1 + *nu));
}

void SpecReader::read_lame(const Object& m, MaterialSpec& out) {
  const auto lambda = m.required("lambda").number();
  const auto mu = m.required("mu").number(kPositive);
  if (!lambda || !mu) return;
  if (*lambda + 2 * *mu / 3 <= 0) {  // the bulk modulus must be positive
    m.required("lambda").fail("a number > -2 mu / 3 = " + format_number(-2 * *mu / 3) +
                              " (a positive bulk modulus)");
    return;
  }
  out.lambda = *lambda;
  out.mu = *mu;
  out.youngs_modulus = *mu * (3 * *lambda + 2 * *mu) / (*lambda + *mu);
  out.poisson_ratio = *lambda / (2 * (*lambda + *mu));
}

/// Coupled heat (read_heat.cpp): C_V > 0, kappa >= 0, alpha >= 0 (the elastic models only);
/// whether the input has a "heat" section is checked there.
void SpecReader::read_thermal(const Object& m, std::optional<MaterialModel> model, MaterialSpec& out) {
  set_if(out.heat_capacity, m.optional("heat_capacity").number(kPositive));
  set_if(out.conductivity, m.optional("conductivity").number(kNonNegative));
  const Value alpha = m.optional("thermal_expansion");
  if (alpha.present() && model && *model != MaterialModel::LinearElastic &&
      *model != MaterialModel::NeoHookean)
    alpha.fail("no \"thermal_expansion\" for a " + std::string(name_of(kModels, *model)) +
               " material (only linear_elastic and neo_hookean have thermal expansion)");
  else
    set_if(out.thermal_expansion, alpha.number(kNonNegative));
}

}  // namespace matpoint::input_detail
