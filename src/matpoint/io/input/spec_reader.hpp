// SpecReader walks the input section by section and fills a Spec (io/input.cpp explains the
// pieces). Its member functions live in one file per section: input/read_*.cpp.
#pragma once

#include "matpoint/io/input/json_value.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint::input_detail {

class SpecReader {
 public:
  explicit SpecReader(Issues& issues) : issues_(issues) {}

  Spec read(const json& root_json);

 private:
  // --- units: names only, for the plots' axes (summary.json echoes them); nothing is converted ---

  void read_units(const Object& units);

  // --- grid ---

  void read_grid(const Object& grid);

  /// mesh (implicit runs): a structured mesh or a Gmsh file; fills the grid from it (read_mesh.cpp).
  void read_mesh(const Object& mesh);
  void read_mesh_file(const Object& mesh);
  void read_mesh_diagonal(const Object& mesh);
  void read_mesh_lines(const Object& mesh);
  void read_dt_by_position(const Object& solver, const Object& implicit, SolverSpec& out);

  /// A number (the same in every direction) or a vector, all > 0.
  std::optional<Triple> read_cell_size(const Value& v) const;

  /// cells = (max - min) / cell_size: a whole number >= 1 per direction, at most kMaxCells in all.
  void read_cell_counts(const Value& cell_size);

  // --- materials ---

  void read_materials(const Value& list);

  MaterialSpec read_material(const Value& v);

  /// The plastic models' keys (material/mohr_coulomb.hpp, drucker_prager.hpp, von_mises.hpp);
  /// refuses them on the other models. Angles in degrees.
  static void read_plasticity(const Object& m, MaterialModel model, MaterialSpec& out);

  /// Mohr-Coulomb strength: c >= 0, 0 < phi < 90 deg, 0 <= psi <= phi, optional linear softening
  /// {"cohesion": c_r, "friction_angle": phi_r, "plastic_strain": eps_s} with c_r <= c,
  /// psi <= phi_r <= phi.
  static void read_friction(const Object& m, MaterialSpec& out);
  /// Mohr-Coulomb's tension cut-off: 0 <= sigma_t < c cot(phi).
  static void read_tension_cutoff(const Object& m, MaterialSpec& out);
  /// J2's optional Johnson-Cook terms.
  static void read_johnson_cook(const Object& jc, MaterialSpec& out);

  /// model "mie_gruneisen" (material/mie_gruneisen.hpp): C0, S, Gamma0 and an optional shear modulus.
  static MaterialSpec read_mie_gruneisen(const Object& m, MaterialSpec& out);

  /// A rigid material: only name, model, density and an optional prescribed velocity (one entry
  /// per axis, each a number or {"table": [[t, v], ...]}; zero by default).
  void read_rigid(const Object& m, MaterialSpec& out) const;

  void read_material_name(const Value& v, MaterialSpec& out);

  /// Exactly one pair: E and nu, or lambda and mu; the other pair is computed from it.
  static void read_elasticity(const Object& m, MaterialSpec& out);

  static void read_young(const Object& m, MaterialSpec& out);

  static void read_lame(const Object& m, MaterialSpec& out);

  /// heat_capacity, conductivity, thermal_expansion (coupled heat; read_materials.cpp).
  static void read_thermal(const Object& m, std::optional<MaterialModel> model, MaterialSpec& out);

  // --- bodies ---

  /// At least `minimum` bodies (0 when the run has FE bodies: an FE body alone is a run).
  void read_bodies(const Value& list, std::size_t minimum);

  BodySpec read_body(const Value& v, std::size_t index);

  /// {"k0": K0 >= 0, "surface": height of the free surface}: an initial geostatic stress, held by
  /// a plastic material's history (the elastic models' stress is a function of F alone).
  void read_geostatic(const Value& v, BodySpec& out) const;
  static void read_prism(const Object& s, BodySpec& out);

  void read_body_material(const Value& v, BodySpec& out) const;

  void read_shape(const Value& v, BodySpec& out) const;

  void read_box(const Object& s, BodySpec& out) const;

  void read_disk(const Object& s, BodySpec& out) const;

  void read_graded_disk(const Object& s, BodySpec& out) const;
  void read_graded_beam(const Object& s, BodySpec& out) const;
  void read_placement(const Object& b, BodySpec& out) const;
  void read_triangle_placement(const Object& b, BodySpec& out) const;

  static void read_polygon(const Object& s, BodySpec& out);

  static std::pair<Triple, Triple> bounding_box(const BodySpec& body, int dim);

  void check_inside_grid(const Value& shape, const BodySpec& body) const;

  /// "reaches 0.2 beyond the x+ side (x = 1.2 > grid.max[0] = 1)": each side the box [lo, hi] crosses.
  [[nodiscard]] std::string overhang_text(const Triple& lo, const Triple& hi) const;

  /// [lo, hi] lies in the grid's box, widened by `relative_tolerance` of its size.
  [[nodiscard]] bool box_inside_grid(const Triple& lo, const Triple& hi, double relative_tolerance) const;

  [[nodiscard]] std::string grid_box_text() const;

  [[nodiscard]] std::string vector_text(const Triple& x) const;

  /// A dim x dim matrix as an array of rows: V += G x.
  void read_velocity_gradient(const Value& v, BodySpec& out) const;

  void read_sine(const Object& s, BodySpec& out) const;

  // --- boundary conditions ---

  void read_conditions(const Value& list);

  /// {"type": "moving_wall", "axis", "position", "material": "below"|"above", "velocity", "depth",
  ///  "stretch_about"} (Nairn 2026 §3.1).
  VelocityConditionSpec read_moving_wall(const Object& c) const;

  VelocityConditionSpec read_condition(const Object& c) const;

  VelocityConditionSpec read_mesh_condition(const Object& c) const;
  /// A structured mesh's boundaries are its sides ("left", ...); a Gmsh mesh's are checked at set-up.
  void check_one_sided_normal(const Object& c, const VelocityConditionSpec& out) const;
  void check_mesh_boundary(const Value& v, const std::string& name) const;
  /// A receding constant C_c > 0 (conditions[].receding, fe_bodies[].interface_receding) needs Q9
  /// elements (or a mesh file, checked when the mesh is built): fails at v otherwise.
  void check_receding_mesh(const Value& v, double receding) const;

  /// "velocity": required for type "velocity" (grid faces, boxes and mesh boundaries alike), refused
  /// otherwise.
  void read_condition_velocity(const Object& c, VelocityConditionSpec& out) const;
  /// "one_sided": true on a fixed or slip face (slip with the face's own normal), not with FMPM/XPIC.
  void read_one_sided(const Value& v, VelocityConditionSpec& out) const;

  /// One-sided conditions decide per step which nodes they hold; the FMPM/XPIC increments would need
  /// that choice cached, so they are refused there.
  void check_one_sided_transfer(const Value& list) const;

  /// Exactly one of "face" and "box".
  void read_region(const Object& c, VelocityConditionSpec& out) const;

  /// The faces of the grid's dimension, e.g. "one of "x-", "x+", "y-", "y+"".
  [[nodiscard]] std::string faces_text() const;

  void read_normal(const Object& c, ConditionKind kind, VelocityConditionSpec& out) const;

  [[nodiscard]] std::string prescribed_velocity_text() const;

  void read_prescribed_velocity(const Value& v, VelocityConditionSpec& out) const;

  /// A number (a constant) or {"table": [[t0, v0], [t1, v1], ...]} with strictly increasing t.
  static std::optional<TimeFunction> read_time_function(const Value& v, const std::string& expected);
  void read_implicit_time_step(const Object& s, const Object& implicit, SolverSpec& out);

  // --- loads, solver, output, checks ---

  void read_loads(const Object& loads);
  /// loads.tractions[k]: {"boundary", "pressure": p(t)} or {"boundary", "traction": [t_x(t), ...]}.
  [[nodiscard]] SurfaceLoadSpec read_surface_load(const Object& o) const;

  void read_solver(const Object& s);

  void read_implicit(const Object& s);
  /// The material models an implicit run takes (neo_hookean log_j; the plastic ones unless small strain).
  void check_implicit_materials(const std::string& type, bool small_strain);
  /// solver.basis and solver.meshfree of an implicit run (the Galerkin meshfree method).
  void read_implicit_basis(const Object& s);
  void check_meshfree_conditions(const std::string& basis);

  static void read_soft_stiffness(const Object& o, ImplicitSpec& m);

  /// solver.max_energy_growth: a number > 0 (run/energy_guard.hpp), or "off".
  static void read_energy_guard(const Value& growth, SolverSpec& out);
  static void read_rebalance(const Value& v, SolverSpec& out);

  /// solver.constrain_old_velocity: Gong 2015's wall treatment (extraction A24): the velocity
  /// conditions also hold on the old node velocities v(1), so a = (v+ - v) / dt and the FLIP
  /// increment carry no wall reaction. The FMPM and XPIC loops apply the conditions themselves.
  static void read_constrain_old_velocity(const Value& v, SolverSpec& out);

  /// solver.artificial_viscosity: {"linear": A1, "quadratic": A2}, NairnMPM's defaults 0.2 and 2.0.
  static void read_artificial_viscosity(const Object& a, SolverSpec& out);

  /// solver.mapping and solver.mls: Gong 2015's IMPM (§5.4) and MLS velocity mapping (§6.6).
  void read_mapping(const Object& s, SolverSpec& out) const;

  /// solver.fmpm (transfer "fmpm") or solver.xpic (transfer "xpic"): Nairn 2026 §2.2-3.4.
  void read_fmpm(const Object& s, SolverSpec& out) const;

  /// The basis's stencil must fit on the grid (shape/stencil_width.hpp).
  void check_stencil_fits();

  /// A run of more than kMaxPlausibleSteps steps without solver.max_steps is almost always a unit
  /// mix-up (end_time in ms against SI moduli, a cell size in m against a grid in mm, ...): refused
  /// with the estimate. dt from solver.dt, or the Courant number with the elastic wave speed
  /// sqrt((lambda + 2 mu) / rho) of the stiffest material (particle speeds are not known yet).
  void check_step_count();

  void read_output(const Object& o);

  /// output.probes: [{"name": "tip", "position": [x, y]}, ...] (docs/input.md#output).
  void read_probes(const Value& list, std::vector<ProbeSpec>& out);

  /// output.checkpoint: every N steps and/or every T wall-clock minutes (docs/input.md#output).
  void read_checkpoint_keys(const Object& c);

  void read_checks(const Value& list);

  static void read_measure(const Value& v, CheckSpec& check);

  // --- contact (Nairn 2026 §3.2; docs/theory/contact.md) ---

  void read_contact(const Value& v);

  // --- fe_bodies (read_fe_bodies.cpp): finite element bodies of an implicit run ---

  void read_fe_bodies(const Value& list);
  void read_fe_material(const Value& v, FeBodySpec& out) const;

  // --- heat (read_heat.cpp): coupled heat conduction, explicit solver only ---

  void read_heat(const Value& v);
  void read_heat_sine(const Object& s);
  void read_thermal_conditions(const Value& list);
  void read_thermal_contact(const Object& h);
  void read_body_temperatures(const Value& list);
  /// Every material's thermal keys against the presence of the "heat" section.
  void check_material_heat(bool heat) const;

  /// "law" (default "stick") and "friction" (Coulomb only, required there).
  static ContactLawSpec read_contact_law(const Object& c);

  [[nodiscard]] std::vector<std::string> field_names(bool by_material) const;

  /// [{"between": [name, name], "law", "friction"}, ...]: the law of one pair of fields.
  void read_contact_pairs(const Value& list, const std::vector<std::string>& names, ContactSpec& out) const;

  /// Contact runs on the explicit solver's per-increment FMPM path with fixed-domain bases.
  void check_contact_solver(const Value& v) const;

  Issues& issues_;
  Spec spec_;
  int dim_ = 0;                  // grid.dim, 0 while unknown (missing or invalid)
  bool grid_ok_ = false;         // the grid has no issue: bodies can be checked against it
  bool names_complete_ = false;  // every material has a valid name: bodies' references can be checked
  bool contact_given_ = false;   // the input has a "contact" section (valid or not)
};

}  // namespace matpoint::input_detail
