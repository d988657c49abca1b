// The input reader, section loads and the solver (docs/input.md).
#include <algorithm>
#include <array>
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
#include "matpoint/core/parallel_session.hpp"
#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"
#include "matpoint/io/memory_estimate.hpp"
#include "matpoint/io/particle_fields.hpp"
#include "matpoint/shape/stencil_width.hpp"

namespace matpoint::input_detail {

void SpecReader::read_loads(const Object& loads) {
  set_if(spec_.loads.gravity, loads.optional("gravity").vector(dim_));
  const Value scale = loads.optional("gravity_scale");
  if (scale.present())
    set_if(spec_.loads.gravity_scale,
           read_time_function(scale, "a number or {\"table\": [[t, scale], ...]}: the factor on gravity"));
  const Value tractions = loads.optional("tractions");
  if (!tractions.present()) return;
  if (!spec_.mesh.enabled) {
    tractions.fail(
        "no tractions unless the input has a mesh (surface loads act on the faces of an implicit "
        "run's mesh boundaries)");
    return;
  }
  if (spec_.mesh.element == MeshElement::BSpline2) {
    tractions.fail(
        "no tractions on a mesh.element \"bspline2\" (surface loads are integrated on Lagrange faces: "
        "\"q4\", \"q9\", \"t3\", \"hex8\" or a mesh file)");
    return;
  }
  for (const auto& item :
       tractions.elements("an array of {\"boundary\", \"pressure\" or \"traction\"} objects"))
    spec_.loads.tractions.push_back(read_surface_load(Object(item, {"boundary", "pressure", "traction"})));
}

SurfaceLoadSpec SpecReader::read_surface_load(const Object& o) const {
  SurfaceLoadSpec out;
  if (!o.valid()) return out;
  if (const auto boundary = o.required("boundary").string()) {
    out.boundary = *boundary;
    check_mesh_boundary(o.required("boundary"), *boundary);
  }
  const Value pressure = o.optional("pressure"), traction = o.optional("traction");
  if (pressure.present() && traction.present()) {
    traction.fail("no traction with a pressure (one surface load per entry)");
  } else if (pressure.present()) {
    out.pressure = read_time_function(
        pressure, "a number or {\"table\": [[t, p], ...]}: the pressure, positive pushing into the body");
  } else if (traction.present()) {
    const std::string expected = "an array of " + std::to_string(dim_) +
                                 " entries, each a number or {\"table\": [[t, value], ...]}: the traction "
                                 "per unit length (area) of the boundary";
    if (!traction.get().is_array() || traction.get().size() != static_cast<std::size_t>(dim_)) {
      traction.fail(expected);
      return out;
    }
    for (std::size_t a = 0; a < traction.get().size(); ++a)
      out.traction[a] = read_time_function(traction.element(a), expected);
  } else {
    o.missing("pressure", "a pressure (a number or a table) or a \"traction\" vector");
  }
  return out;
}

void SpecReader::read_solver(const Object& s) {
  SolverSpec& out = spec_.solver;
  set_if(out.kind, s.optional("type").choice(kSolverKinds));
  if (out.is_implicit()) {
    read_implicit(s);
    return;
  }
  if (s.has("implicit"))
    s.optional("implicit")
        .fail("no implicit options unless solver.type is \"implicit_mpm\" or \"implicit_ul\"");
  if (s.has("meshfree"))
    s.optional("meshfree")
        .fail("no meshfree unless solver.type is \"implicit_ul\" with basis \"mls\" or \"lme\"");
  set_if(out.scheme, s.optional("scheme").choice(kSchemes));
  const auto transfer = s.optional("transfer").choice(kTransfers);
  set_if(out.transfer, transfer);
  if (out.transfer == VelocityTransfer::FMPM) out.position_alpha = 0.5;  // Nairn 2026 §2.1: consistent
  set_if(out.position_alpha, s.optional("position_alpha").number(kUnitInterval));
  read_fmpm(s, out);
  const Value flip_fraction = s.optional("flip_fraction");
  if (out.transfer == VelocityTransfer::Blend)
    out.flip_fraction = flip_fraction.number(kUnitInterval).value_or(0.99);
  else if (flip_fraction.present() && (transfer || !s.has("transfer")))
    flip_fraction.fail("no flip_fraction unless transfer is \"blend\"");
  // Without a basis: quadratic B-splines, the user guide's recommendation (no cell-crossing
  // noise); linear under mapping "impm", whose cell quadrature needs it (Gong 2015 §5.3).
  const bool impm = s.optional("mapping").present() && s.optional("mapping").get() == "impm";
  out.shape = impm ? ShapeKind::Linear : ShapeKind::BSpline2;
  set_if(out.shape, s.optional("basis").choice(kShapeKinds));
  if (s.has("shape"))  // the key's old name, easily confused with bodies[].shape (a body's geometry)
    s.optional("shape").fail(
        "no key shape here: the basis functions are solver.basis (renamed from solver.shape)");
  read_mapping(s, out);
  set_if(out.deformation_update, s.optional("deformation_update").choice(kDeformationUpdates));
  out.dt = s.optional("dt").number(kPositive);
  const Value courant = s.optional("courant");
  if (s.has("dt") && courant.present())
    courant.fail("no courant when dt is given (one of dt or courant)");
  else
    set_if(out.courant, courant.number({0, 1, true, false}));
  set_if(out.end_time, s.required("end_time").number(kPositive));
  set_if(out.max_steps, s.optional("max_steps").integer(0));
  set_if(out.mass_tolerance, s.optional("mass_tolerance").number({0, 1, false, true}));
  read_constrain_old_velocity(s.optional("constrain_old_velocity"), out);
  read_energy_guard(s.optional("max_energy_growth"), out);
  read_artificial_viscosity(Object(s.optional("artificial_viscosity"), {"linear", "quadratic"}), out);
  read_rebalance(s.optional("rebalance"), out);
}

/// solver.type "implicit_mpm" (Aulisa & Capodaglio's particle-Newmark MPM) or "implicit_ul"
/// (Iaconeta 2017's updated-Lagrangian MPM with Newmark on the grid) on the input's mesh. The
/// explicit solver's keys are refused; end_time and dt (or a dt_schedule) are required.
void SpecReader::read_implicit(const Object& s) {
  SolverSpec& out = spec_.solver;
  const std::string type = out.kind == SolverKind::ImplicitUl ? "implicit_ul" : "implicit_mpm";
  if (!spec_.mesh.enabled)
    s.optional("type").fail("\"explicit\" unless the input has a mesh (solver.type \"" + type +
                            "\" runs on one)");
  for (const char* key : {"scheme", "transfer", "position_alpha", "flip_fraction", "fmpm", "xpic", "shape",
                          "mapping", "mls", "deformation_update", "courant", "mass_tolerance",
                          "constrain_old_velocity", "artificial_viscosity", "rebalance"})
    if (s.has(key))
      s.optional(key).fail(std::string("no ") + key + " with solver.type \"" + type +
                           "\" (an explicit solver's key)");
  set_if(out.end_time, s.required("end_time").number(kPositive));
  set_if(out.max_steps, s.optional("max_steps").integer(0));
  read_energy_guard(s.optional("max_energy_growth"), out);
  const Object o(s.optional("implicit"),
                 {"beta", "gamma", "initial_acceleration", "newton", "linear_solver", "soft_stiffness",
                  "receding_gradient", "max_step_cuts", "dt_schedule", "dt_by_position", "adaptive_dt",
                  "analysis", "kinematics"});
  ImplicitSpec& m = out.implicit;
  if (out.kind == SolverKind::ImplicitUl) m.beta = 0.25;  // Iaconeta 2017 §4.1.1: zeta = 0.25, lambda = 0.5
  const auto analysis = o.optional("analysis").string();
  if (analysis && *analysis != "dynamic" && *analysis != "static")
    o.optional("analysis").fail("\"dynamic\" or \"static\" (no inertia: equilibrium under each step's load)");
  if (analysis) m.static_analysis = *analysis == "static";
  if (out.kind == SolverKind::ImplicitUl && !m.static_analysis && spec_.mesh.file.empty() &&
      spec_.mesh.element == MeshElement::Q9)
    issues_.add(
        "mesh.element", "\"q9\"",
        "\"q4\" or \"hex8\" for a dynamic solver.type \"implicit_ul\" (Q9 only with implicit.analysis "
        "\"static\"): the projection of the particles' momentum to the nodes (Iaconeta 2017 eqs. "
        "(38)-(41)) needs shape functions >= 0, and quadratic ones are negative in places "
        "(docs/theory/implicit.md)");
  const auto kinematics = o.optional("kinematics").string();
  if (kinematics && *kinematics != "finite" && *kinematics != "small")
    o.optional("kinematics").fail("\"finite\" or \"small\" (geometrically linear with Hooke's law)");
  if (kinematics) m.small_strain = *kinematics == "small";
  check_implicit_materials(type, m.small_strain);
  read_implicit_time_step(s, o, out);
  set_if(m.beta, o.optional("beta").number({0, 0.5, true, false}));
  set_if(m.gamma, o.optional("gamma").number({0, 1, false, false}));
  set_if(m.initial_acceleration_from_body_force,
         o.optional("initial_acceleration").choice(kInitialAccelerations));
  set_if(m.linear_solver, o.optional("linear_solver").choice(kLinearSolvers));
  if (m.linear_solver == LinearSolverChoice::Petsc && !ParallelSession::built_with_petsc())
    o.optional("linear_solver")
        .fail(
            "\"umfpack\", \"klu\", \"bicgstab\" or \"gmres\": this build lacks PETSc (build with cmake "
            "-DMATPOINT_PETSC=ON, or run scripts/setup.sh --mpi)");
  set_if(m.max_step_cuts, o.optional("max_step_cuts").integer(0, 30));
  const auto corrected = o.optional("receding_gradient").string();
  if (corrected && *corrected != "corrected" && *corrected != "uncorrected")
    o.optional("receding_gradient")
        .fail(
            "\"corrected\" or \"uncorrected\" (the paper does not say which; \"corrected\" is the authors' "
            "code)");
  if (corrected) m.receding_in_gradient = *corrected == "corrected";
  const Object n(o.optional("newton"),
                 {"increment_tolerance", "max_iterations", "residual_tolerance", "line_search"});
  set_if(m.increment_tolerance, n.optional("increment_tolerance").number({0, 1, true, true}));
  set_if(m.max_iterations, n.optional("max_iterations").integer(1, 1000));
  set_if(m.residual_tolerance, n.optional("residual_tolerance").number({0, 1, false, true}));
  set_if(m.line_search, n.optional("line_search").boolean());
  read_soft_stiffness(Object(o.optional("soft_stiffness"), {"flag_rule", "table"}), m);
  read_implicit_basis(s);
}

/// solver.implicit.dt_by_position: {"axis": "y", "dt": {"table": [[coordinate, dt], ...]}}: the step
/// as a function of the lowest particle's coordinate (Aulisa & Capodaglio's Test D steps finer near the
/// plate, extraction A18), instead of solver.dt, dt_schedule and adaptive_dt.
void SpecReader::read_dt_by_position(const Object& s, const Object& o, SolverSpec& out) {
  for (const char* key : {"dt_schedule", "adaptive_dt"})
    if (o.has(key)) o.optional(key).fail(std::string("no ") + key + " with dt_by_position (one of them)");
  if (s.has("dt")) s.optional("dt").fail("no dt with solver.implicit.dt_by_position (one of them)");
  const Object p(o.optional("dt_by_position"), {"axis", "dt"});
  if (!p.valid()) return;
  if (const auto axis = p.required("axis").choice(kAxes)) {
    if (dim_ != 0 && *axis >= dim_)
      p.required("axis").fail(dim_ == 2 ? "\"x\" or \"y\"" : "\"x\", \"y\" or \"z\"");
    out.implicit.dt_position_axis = *axis;
  }
  const std::string expected = "a time step > 0 or {\"table\": [[coordinate, dt], ...]} with every dt > 0";
  out.implicit.dt_by_position = read_time_function(p.required("dt"), expected);
  if (out.implicit.dt_by_position)
    for (double dt : out.implicit.dt_by_position->values)
      if (!(dt > 0)) {
        p.required("dt").fail(expected);
        break;
      }
}

/// The implicit time step: solver.dt (fixed, or the first adaptive step), or
/// solver.implicit.dt_schedule (a time function, without solver.dt); adaptive_dt needs solver.dt.
void SpecReader::read_implicit_time_step(const Object& s, const Object& o, SolverSpec& out) {
  const Value schedule = o.optional("dt_schedule");
  const Value adaptive = o.optional("adaptive_dt");
  if (o.has("dt_by_position")) {
    read_dt_by_position(s, o, out);
    return;
  }
  if (schedule.present()) {
    if (s.has("dt")) s.optional("dt").fail("no dt with solver.implicit.dt_schedule (one of them)");
    if (adaptive.present()) adaptive.fail("no adaptive_dt with dt_schedule (one of them)");
    const std::string expected = "a time step > 0 or {\"table\": [[t, dt], ...]} with every dt > 0";
    out.implicit.dt_schedule = read_time_function(schedule, expected);
    if (out.implicit.dt_schedule)
      for (double dt : out.implicit.dt_schedule->values)
        if (!(dt > 0)) {
          schedule.fail(expected);
          break;
        }
    return;
  }
  out.dt = s.required("dt").number(kPositive);
  if (!adaptive.present()) return;
  ImplicitSpec::Adaptive& a = out.implicit.adaptive;
  const Object ad(adaptive, {"min", "max", "easy_iterations", "hard_iterations", "factor"});
  a.enabled = true;
  set_if(a.min, ad.required("min").number(kPositive));
  set_if(a.max, ad.required("max").number(kPositive));
  set_if(a.easy_iterations, ad.optional("easy_iterations").integer(0, 1000));
  set_if(a.hard_iterations, ad.optional("hard_iterations").integer(1, 1000));
  set_if(a.factor, ad.optional("factor").number({1, 10, false, true}));
  if (a.max < a.min) ad.optional("max").fail("max >= min (" + format_number(a.min) + ")");
  if (out.dt && (*out.dt < a.min || *out.dt > a.max))
    s.optional("dt").fail("within adaptive_dt's [min, max] = [" + format_number(a.min) + ", " +
                          format_number(a.max) + "]");
  if (a.hard_iterations <= a.easy_iterations)
    ad.optional("hard_iterations")
        .fail("more than easy_iterations (" + std::to_string(a.easy_iterations) + ")");
}

/// soft_stiffness: {"flag_rule": "paper" | "code", "table": [[M, C_E], ...]}: C_E applies to the
/// elements with M_E < M (the first row that fits; eq. (26), the paper's eqs. (50)/(51)); the
/// bounds increase, C_E >= 0 does not increase with M (the paper: C_E non-increasing, 0 at M_E = N_E).
void SpecReader::read_soft_stiffness(const Object& o, ImplicitSpec& m) {
  set_if(m.flag_rule, o.optional("flag_rule").choice(kFlagRules));
  const Value table = o.optional("table");
  const std::string expected =
      "an array of [M, C_E] rows: whole numbers M increasing in 1..27, C_E >= 0 not increasing";
  int last_bound = 0;
  double last_value = kInf;
  for (const auto& row : table.elements(expected)) {
    const auto pair = row.get();
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number_integer() || !pair[1].is_number()) {
      row.fail(expected);
      continue;
    }
    const long bound = pair[0].get<long>();
    const double value = pair[1].get<double>();
    if (bound <= last_bound || bound > 27 || !(value >= 0) || !std::isfinite(value) || value > last_value) {
      row.fail(expected);
      continue;
    }
    m.soft_stiffness.emplace_back(static_cast<int>(bound), value);
    last_bound = static_cast<int>(bound), last_value = value;
  }
}

/// solver.max_energy_growth: a number > 0 (run/energy_guard.hpp), or "off".
void SpecReader::read_energy_guard(const Value& growth, SolverSpec& out) {
  if (!growth.present()) return;
  const json& j = growth.get();
  if (j.is_string() && j.get_ref<const std::string&>() == "off")
    out.max_energy_growth.reset();
  else if (j.is_number() && j.get<double>() > 0 && std::isfinite(j.get<double>()))
    out.max_energy_growth = j.get<double>();
  else
    growth.fail("a number > 0, or \"off\"");
}

/// solver.rebalance: "off", or {"imbalance": a number > 1, "min_steps": an integer >= 1}
/// (parallel/box_partition.hpp; checked at every re-sort, docs/scale-out.md §10).
void SpecReader::read_rebalance(const Value& v, SolverSpec& out) {
  if (!v.present()) return;
  if (v.get().is_string() && v.get().get_ref<const std::string&>() == "off") {
    out.rebalance.enabled = false;
    return;
  }
  if (!v.get().is_object()) {
    v.fail("\"off\", or an object {\"imbalance\": a number > 1, \"min_steps\": an integer >= 1}");
    return;
  }
  const Object r(v, {"imbalance", "min_steps"});
  set_if(out.rebalance.imbalance, r.optional("imbalance").number({1, kInf, true, false}));
  set_if(out.rebalance.min_steps, r.optional("min_steps").integer(1));
}

/// solver.constrain_old_velocity: Gong 2015's wall treatment (extraction A24): the velocity
/// conditions also hold on the old node velocities v(1), so a = (v+ - v) / dt and the FLIP
/// increment carry no wall reaction. The FMPM and XPIC loops apply the conditions themselves.
void SpecReader::read_constrain_old_velocity(const Value& v, SolverSpec& out) {
  set_if(out.constrain_old_velocity, v.boolean());
  if (out.constrain_old_velocity &&
      (out.transfer == VelocityTransfer::FMPM || out.transfer == VelocityTransfer::XPIC))
    v.fail(
        "false with transfer \"fmpm\" or \"xpic\" (their loops apply the velocity conditions to "
        "every increment, Nairn 2026 Table 2)");
}

/// solver.artificial_viscosity: {"linear": A1, "quadratic": A2}, NairnMPM's defaults 0.2 and 2.0.
void SpecReader::read_artificial_viscosity(const Object& a, SolverSpec& out) {
  if (!a.valid()) return;
  out.av_linear = a.optional("linear").number(kNonNegative).value_or(0.2);
  out.av_quadratic = a.optional("quadratic").number(kNonNegative).value_or(2.0);
}

/// solver.mapping and solver.mls: Gong 2015's IMPM (§5.4) and MLS velocity mapping (§6.6).
void SpecReader::read_mapping(const Object& s, SolverSpec& out) const {
  const Value mapping = s.optional("mapping");
  set_if(out.mapping, mapping.choice(kMappings));
  const Value mls_value = s.optional("mls");
  if (out.mapping == Mapping::MPM) {
    if (mls_value.present()) mls_value.fail("no mls unless mapping is \"impm\" or \"mls_velocity\"");
    return;
  }
  if (out.mapping == Mapping::IMPM && out.shape != ShapeKind::Linear)
    mapping.fail(
        "\"impm\" with basis \"linear\" (the cell quadrature uses the bilinear N_i), or "
        "\"mls_velocity\" for the other bases");
  if (out.transfer == VelocityTransfer::FMPM || out.transfer == VelocityTransfer::XPIC)
    mapping.fail("\"mpm\" with transfer \"fmpm\" or \"xpic\" (their passes re-map the momentum by mass)");
  const Object mls(mls_value, {"degree", "quadrature", "cell_volume"});
  set_if(out.mls.degree, mls.optional("degree").integer(0, 1));
  for (const char* key : {"quadrature", "cell_volume"})
    if (out.mapping != Mapping::IMPM && mls.has(key))
      mls.optional(key).fail(std::string("no ") + key + " unless mapping is \"impm\"");
  set_if(out.mls.quadrature, mls.optional("quadrature").choice(kCellQuadratures));
  set_if(out.mls.cell_volume, mls.optional("cell_volume").choice(kCellVolumes));
}

/// solver.fmpm (transfer "fmpm") or solver.xpic (transfer "xpic"): Nairn 2026 §2.2-3.4.
void SpecReader::read_fmpm(const Object& s, SolverSpec& out) const {
  const bool fmpm = out.transfer == VelocityTransfer::FMPM, xpic = out.transfer == VelocityTransfer::XPIC;
  for (const char* key : {"fmpm", "xpic"}) {
    const Value v = s.optional(key);
    if (v.present() && !(key == std::string_view("fmpm") ? fmpm : xpic))
      v.fail(std::string("no ") + key + " unless transfer is \"" + key + "\"");
  }
  if (xpic) {
    const Object x(s.optional("xpic"), {"order"});
    set_if(out.fmpm.order, x.optional("order").integer(1, kMaxFmpmOrder));
    return;
  }
  if (!fmpm) return;
  const Object f(s.optional("fmpm"),
                 {"order", "blend", "dynamic", "periodic", "boundary_method", "recursion"});
  FmpmSpec& k = out.fmpm;
  set_if(k.order, f.optional("order").integer(1, kMaxFmpmOrder));
  const Object blend(f.optional("blend"), {"with", "factor"});
  if (blend.valid()) {
    set_if(k.blend_with, blend.required("with").integer(1, 2));
    set_if(k.blend_factor, blend.required("factor").number(kUnitInterval));
  }
  const Object dynamic(f.optional("dynamic"), {"measure", "limit"});
  if (dynamic.valid()) {
    set_if(k.measure, dynamic.required("measure").choice(kFmpmMeasures));
    set_if(k.limit, dynamic.required("limit").number(kPositive));
  }
  const Object periodic(f.optional("periodic"), {"courant", "steps", "time"});
  if (periodic.valid()) {
    int given = 0;
    if (const auto c = periodic.optional("courant").number(kPositive)) {
      k.period = FmpmPeriod::Courant, k.period_value = *c, ++given;
    }
    if (const auto n = periodic.optional("steps").integer(1)) {
      k.period = FmpmPeriod::Steps, k.period_value = static_cast<double>(*n), ++given;
    }
    if (const auto t = periodic.optional("time").number(kPositive)) {
      k.period = FmpmPeriod::Time, k.period_value = *t, ++given;
    }
    if (given != 1) periodic.value().fail("an object with exactly one of the keys courant, steps or time");
  }
  set_if(k.boundary_method, f.optional("boundary_method").choice(kFmpmBoundaryMethods));
  set_if(k.recursion, f.optional("recursion").choice(kFmpmRecursions));
  if (k.recursion == FmpmRecursion::Binomial && (k.blend_with > 0 || k.measure != FmpmMeasure::None))
    f.optional("recursion").fail("\"incremental\" with blend or dynamic (eq. 4 has no per-increment step)");
}

/// The basis's stencil must fit on the grid (shape/stencil_width.hpp).
void SpecReader::check_stencil_fits() {
  const int fewest = minimum_cells(spec_.solver.shape);
  for (int a = 0; a < dim_; ++a)
    if (spec_.grid.cells[a] < fewest) {
      issues_.add("grid.cell_size", format_number(spec_.grid.cell_size[a]),
                  "at least " + std::to_string(fewest) + " cells per direction for solver.basis \"" +
                      std::string(name_of(kShapeKinds, spec_.solver.shape)) + "\" (its stencil is " +
                      std::to_string(fewest + 1) + " nodes wide); the grid has " +
                      std::to_string(spec_.grid.cells[a]) + " along axis " + std::to_string(a));
      return;
    }
}

/// A run of more than kMaxPlausibleSteps steps without solver.max_steps is almost always a unit
/// mix-up (end_time in ms against SI moduli, a cell size in m against a grid in mm, ...): refused
/// with the estimate. dt from solver.dt, or the Courant number with the elastic wave speed
/// sqrt((lambda + 2 mu) / rho) of the stiffest material (particle speeds are not known yet).
void SpecReader::check_step_count() {
  const SolverSpec& solver = spec_.solver;
  if (solver.max_steps > 0) return;
  double dt = solver.dt.value_or(0.0);
  if (!solver.dt) {
    double speed = 0.0, h = kInf;
    for (const auto& m : spec_.materials)
      speed = std::max(speed, std::sqrt((m.lambda + 2.0 * m.mu) / m.density));
    for (int a = 0; a < dim_; ++a) h = std::min(h, spec_.grid.cell_size[a]);
    if (!(speed > 0.0)) return;
    dt = solver.courant * h / speed;
  }
  const double steps = solver.end_time / dt;
  if (steps <= kMaxPlausibleSteps) return;
  issues_.add("solver.end_time", format_number(solver.end_time),
              "a run of at most 1e9 time steps without solver.max_steps; this one needs about " +
                  format_number(std::round(steps)) + " steps of dt = " + format_number(dt) +
                  " (check the units of end_time, cell_size, E and density, or set solver.max_steps)");
}

/// The models an implicit run takes: neo_hookean with volumetric "log_j" (Aulisa & Capodaglio eq.
/// (12), Iaconeta 2017 §7.1) and, with finite kinematics, the Hencky plastic models (Iaconeta 2017
/// §7.2) through their consistent tangents (implicit/implicit_material.hpp).
void SpecReader::check_implicit_materials(const std::string& type, bool small_strain) {
  for (std::size_t k = 0; k < spec_.materials.size(); ++k) {
    const MaterialSpec& material = spec_.materials[k];
    const bool plastic = material.model == MaterialModel::MohrCoulomb ||
                         material.model == MaterialModel::DruckerPrager ||
                         material.model == MaterialModel::VonMises;
    const bool neo_hookean =
        material.model == MaterialModel::NeoHookean && material.volumetric == NeoHookeanVolumetric::LogJ;
    if (plastic && small_strain)
      issues_.add("materials[" + std::to_string(k) + "].model", "\"" + material.name + "\"",
                  "an elastic model (neo_hookean) under solver.implicit.kinematics \"small\" (Hooke's law on "
                  "the elastic constants, a check against linear theory, has no plasticity)");
    else if (!plastic && !neo_hookean)
      issues_.add(
          "materials[" + std::to_string(k) + "].model", "\"" + material.name + "\"",
          "model \"neo_hookean\" with volumetric \"log_j\" (Aulisa & Capodaglio eq. (12), Iaconeta "
          "2017 §7.1) or \"mohr_coulomb\", \"drucker_prager\", \"von_mises\" (Iaconeta 2017 §7.2) under "
          "solver.type \"" +
              type + "\"");
  }
}

}  // namespace matpoint::input_detail

namespace matpoint::input_detail {

/// solver.basis of an implicit run: "mesh" (the elements' functions: MPM), or "mls" / "lme", the
/// Galerkin meshfree method of Iaconeta 2017 §4.2 (the mesh's nodes become Lagrangian nodes with
/// Newmark history, the particles its integration points), with solver.meshfree's parameters as
/// multiples of the nodal spacing h (extraction A5). Its step holds fixed and slip dofs at du = 0 and
/// knows neither prescribed motion, one-sided walls, surface loads nor small-strain kinematics.
void SpecReader::read_implicit_basis(const Object& s) {
  ImplicitSpec& m = spec_.solver.implicit;
  set_if(m.basis, s.optional("basis").choice(kImplicitBases));
  const Object f(s.optional("meshfree"),
                 {"radius_factor", "dilation_factor", "gamma", "min_nodes", "lme_max_nodes", "spacing",
                  "mls_weight", "delete_failed_points", "node_history"});
  if (m.basis == ImplicitBasis::Mesh) {
    if (s.has("meshfree"))
      s.optional("meshfree").fail("no meshfree unless solver.basis is \"mls\" or \"lme\"");
    return;
  }
  const bool mls = m.basis == ImplicitBasis::Mls;
  const std::string basis = mls ? "\"mls\"" : "\"lme\"";
  if (spec_.mesh.element == MeshElement::BSpline2)
    s.optional("basis").fail(
        "\"mesh\" with mesh.element \"bspline2\" (the meshfree nodes are a Lagrange "
        "mesh's nodes; a B-spline patch's are control points)");
  if (spec_.solver.kind != SolverKind::ImplicitUl)
    s.optional("basis").fail(
        "\"mesh\" under solver.type \"implicit_mpm\" (the Galerkin meshfree method, Iaconeta 2017 §4.2, "
        "keeps Newmark's history at its nodes: solver.type \"implicit_ul\")");
  MeshfreeSpec& out = m.meshfree;
  set_if(out.radius_factor, f.optional("radius_factor").number(kPositive));
  set_if(out.spacing, f.optional("spacing").number(kPositive));
  static constexpr std::array<const char*, 2> kLmeOnly{"gamma", "lme_max_nodes"};
  static constexpr std::array<const char*, 3> kMlsOnly{"dilation_factor", "min_nodes", "mls_weight"};
  const auto refuse = [&](const auto& keys) {
    for (const char* key : keys)
      if (f.has(key)) f.optional(key).fail(std::string("no ") + key + " with solver.basis " + basis);
  };
  mls ? refuse(kLmeOnly) : refuse(kMlsOnly);
  out.dilation_factor = f.optional("dilation_factor").number(kPositive);
  set_if(out.gamma, f.optional("gamma").number(kPositive));
  if (const auto n = f.optional("min_nodes").integer(0, 1000)) out.min_nodes = static_cast<int>(*n);
  if (const auto n = f.optional("lme_max_nodes").integer(0, 1000)) out.lme_max_nodes = static_cast<int>(*n);
  set_if(out.mls_truncated_weight, f.optional("mls_weight").choice(kMlsWeights));
  set_if(out.delete_failed_points, f.optional("delete_failed_points").boolean());
  set_if(out.carried_node_history, f.optional("node_history").choice(kNodeHistories));
  check_meshfree_conditions(basis);
}

/// What the meshfree step does not take (read_implicit_basis).
void SpecReader::check_meshfree_conditions(const std::string& basis) {
  const std::string with = " with solver.basis " + basis;
  for (std::size_t k = 0; k < spec_.conditions.size(); ++k) {
    const VelocityConditionSpec& c = spec_.conditions[k];
    const std::string path = "boundary_conditions[" + std::to_string(k) + "]";
    if (c.kind != ConditionKind::Fixed && c.kind != ConditionKind::Slip)
      issues_.add(path + ".type", "\"velocity\"",
                  "\"fixed\" or \"slip\"" + with + " (the meshfree step holds its nodes at du = 0)");
    if (c.receding > 0)
      issues_.add(path + ".receding", format_number(c.receding),
                  "0" + with + " (an MPM element's correction)");
  }
  if (!spec_.loads.tractions.empty())
    issues_.add("loads.tractions", "[...]",
                "none" + with + " (surface loads act on mesh faces, which the meshfree body does not keep)");
  if (spec_.solver.implicit.small_strain)
    issues_.add("solver.implicit.kinematics", "\"small\"", "\"finite\"" + with);
  if (!spec_.solver.implicit.soft_stiffness.empty())
    issues_.add("solver.implicit.soft_stiffness", "{...}",
                "none" + with + " (an MPM element's stiffness for nearly empty cells)");
}

}  // namespace matpoint::input_detail
