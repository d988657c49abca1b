// The implicit MPMs (Aulisa & Capodaglio's particle Newmark, Iaconeta 2017's updated-Lagrangian grid
// Newmark; dynamic or static) as the shared run loop sees it
// (run/run_loop.hpp lists the interface): the input's mesh and conditions turned into the stepper
// of implicit/particle_newmark/, the particles and materials of the explicit set-up
// (build_simulation), the time-step control (step_size_control.hpp), and the step-cutting policy:
// a step whose Newton iteration fails is halved and retried (solver.implicit.max_step_cuts times),
// then the run stops with exit 3 naming the step, the time and Newton's residual history, its last
// output kept. A checkpoint holds the particle accelerations and host elements, so a restart
// continues the run bit for bit (same thread count).
#pragma once

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "matpoint/analysis/probes.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/fem/fe_output.hpp"
#include "matpoint/implicit/implicit_run_common.hpp"
#include "matpoint/implicit/particle_newmark/particle_newmark_stepper.hpp"
#include "matpoint/implicit/step_size_control.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/mesh/mesh.hpp"
#include "matpoint/mesh/mesh_vtu.hpp"
#include "matpoint/run/other_bodies_energy.hpp"
#include "matpoint/run/run_summary.hpp"

namespace matpoint::implicit {

template <int D>
ParticleNewmarkOptions<D> stepper_options(const Spec& spec) {
  const ImplicitSpec& in = spec.solver.implicit;
  ParticleNewmarkOptions<D> o;
  o.newmark = {in.beta, in.gamma};
  for (int a = 0; a < D; ++a) o.gravity[a] = spec.loads.gravity[a];
  o.initial_acceleration_from_body_force = in.initial_acceleration_from_body_force;
  o.flag_rule = in.flag_rule == SoftStiffnessRule::Code ? FlagRule::Code : FlagRule::Paper;
  for (const auto& [below, value] : in.soft_stiffness) o.soft_stiffness.pieces.push_back({below, value});
  o.receding_in_gradient = in.receding_in_gradient;
  o.newmark_at_grid = spec.solver.kind == SolverKind::ImplicitUl;
  o.static_analysis = in.static_analysis;
  o.small_strain = in.small_strain;
  o.newton = newton_options(in);
  o.linear = linear_solver_options(in);
  return o;
}

template <class E>
class ImplicitMpmSolver {
 public:
  static constexpr int D = E::kDim;

  /// Throws InputError (nothing written yet) for what only the set-up finds (an empty body, a
  /// boundary the mesh does not have, a particle outside the mesh).
  ImplicitMpmSolver(const Spec& spec, mesh::Mesh<D> background)
      : spec_(spec),
        sim_(build_simulation<D>(without_conditions(spec))),
        mesh_(std::move(background)),
        step_size_(spec.solver) {
    // Iaconeta's projection to the nodes (eqs. (38)-(41), nodal_projection.hpp) divides by
    // sum_p N_I m_p: quadratic elements (Q9, T6) have negative shape values and nodal masses near 0
    // or below. A static analysis has no projection.
    if (spec.solver.kind == SolverKind::ImplicitUl && !E::kNonNegative &&
        !spec.solver.implicit.static_analysis)
      throw InputError({{"mesh.file", spec.mesh.file,
                         "a mesh of linear elements (T3, Q4, Hex8) for a dynamic solver.type \"implicit_ul\" "
                         "(quadratic ones only with implicit.analysis \"static\"; the projection of eqs. "
                         "(38)-(41) needs shape functions >= 0)"}});
    std::vector<char> dirichlet(static_cast<std::size_t>(mesh_.node_count() * D), 0);
    std::vector<char> on_condition(static_cast<std::size_t>(mesh_.node_count()), 0);
    std::map<std::pair<Index, int>, double> receding;
    for (std::size_t k = 0; k < spec.conditions.size(); ++k) {
      const VelocityConditionSpec& c = spec.conditions[k];
      for (Index n : boundary_nodes(mesh_, c, k)) {
        on_condition[static_cast<std::size_t>(n)] = 1;
        for (int a = 0; a < D; ++a) {
          const bool moving = c.kind == ConditionKind::Velocity && c.velocity[static_cast<std::size_t>(a)];
          if (c.kind == ConditionKind::Fixed || (c.kind == ConditionKind::Slip && a == c.normal_axis) ||
              moving)
            dirichlet[static_cast<std::size_t>(n * D + a)] = 1;
          if (moving) moving_dofs_.push_back({n * D + a, &*c.velocity[static_cast<std::size_t>(a)]});
        }
      }
      if (c.receding > 0)
        if (const auto faces = mesh_.boundary_faces.find(c.boundary); faces != mesh_.boundary_faces.end())
          for (const auto& face : faces->second) receding[face] = c.receding;
    }
    collect_loaded_faces();
    fem::FeBodies<E> fe = fe_bodies();
    if (!fe.empty()) {
      add_interface_receding(fe, receding);
      for (const Index n : interface_nodes(fe)) on_condition[static_cast<std::size_t>(n)] = 1;  // A13
      check_particles_outside(fe);
    }
    auto options = stepper_options<D>(spec);
    options.one_sided = one_sided_nodes(mesh_, spec);
    if (!options.one_sided.empty()) options.body_contains = body_shape_test<D>(spec);
    options.gravity = gravity_at(0.0);
    options.not_fully_active = on_condition;  // A13 (b): boundary nodes count as not fully active
    try {
      stepper_.emplace(mesh_, implicit_materials(sim_), options, std::move(dirichlet), std::move(receding),
                       std::move(fe));
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& error) {  // the reset extension (8b) has no unique solution
      throw InputError({{"fe_bodies", "the mesh's background grid", error.what()}});
    }
    stepper_->initialize(sim_.particles, state_);
    previous_x_ = sim_.particles.x;
    for (const FeBodySpec& body : spec.fe_bodies) fe_takes_gravity_ = fe_takes_gravity_ || body.gravity;
    set_node_probes(spec);
  }
  ImplicitMpmSolver(const ImplicitMpmSolver&) = delete;
  ImplicitMpmSolver& operator=(const ImplicitMpmSolver&) = delete;

  Simulation<D>& sim() { return sim_; }
  [[nodiscard]] const Simulation<D>& sim() const { return sim_; }
  [[nodiscard]] const mesh::Mesh<D>& mesh() const { return mesh_; }

  [[nodiscard]] const ImplicitTotals& totals() const { return totals_; }
  /// The FE bodies' state (empty without fe_bodies).
  [[nodiscard]] const fem::FeBodies<E>& fe_bodies_state() const { return stepper_->fe_bodies(); }
  /// x~: where the particles are located (the FE bodies' nodes deformed, the background extended).
  [[nodiscard]] const std::vector<Vec<D>>& reference_nodes() const { return stepper_->reference_nodes(); }
  /// The last Newton solve: status and residual history (tests print its convergence).
  [[nodiscard]] const NewtonResult& last_newton() const { return last_newton_; }
  /// The nodal displacement of the last step (node-major; the whole displacement in a single-step
  /// static analysis, which starts from the undeformed mesh).
  [[nodiscard]] const Eigen::VectorXd& last_nodal_increment() const { return stepper_->last_increment(); }

  /// An output time one to two steps away is reached in two equal steps, never a full step and a
  /// tiny one (run/run_loop.hpp steps_to_land).
  static constexpr bool kEvenStepsToLand = true;
  /// The energy guard after every step (run/energy_guard.hpp): a step costs a Newton solve.
  static constexpr bool kCheckEnergyEveryStep = true;

  /// The next step: solver.dt, the schedule's, or the adaptive one (cut steps are retried
  /// inside step()).
  [[nodiscard]] double time_step() const {
    if (!step_size_.by_position()) return step_size_.next(sim_.time);
    const int axis = spec_.solver.implicit.dt_position_axis;
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& x : sim_.particles.x) lowest = std::min(lowest, x[axis]);
    return step_size_.next(sim_.time, lowest);
  }

  /// Advances by h: one Newton solve, or after a failure 2, 4, ... sub-steps (at most
  /// max_step_cuts halvings); throws NumericalFailure when even the smallest sub-step fails.
  void step(double h) {
    StepReport report;
    const auto attempt = [&](double done, double sub) {
      const Vec<D> gravity = gravity_at(sim_.time + done + sub);  // at the end of the sub-step
      stepper_->set_gravity(gravity);
      stepper_->set_prescribed(prescribed_increments(sim_.time + done, sim_.time + done + sub));
      stepper_->set_face_loads(face_loads_at(sim_.time + done + sub), face_loads_at(sim_.time + done));
      if (fe_takes_gravity_) fe_displacement_before_ = stepper_->fe_bodies().displacement;
      report = stepper_->step(sim_.particles, state_, sub);
      last_newton_ = report.newton;
      totals_.assembly_seconds += report.assembly_seconds;
      marks_.newton_residual = report.newton.final_residual_norm;
      if (report.ok()) {
        account_gravity_work<D>(sim_, previous_x_, sub, gravity);
        if (fe_takes_gravity_) fe_external_work_ += fe_gravity_work(gravity);
        sim_.external_work += report.boundary_work + report.load_work;
        defect_work_ += report.defect_work;
      }
      // every solve of the step counts (one-sided walls: several)
      return SubStepOutcome{report.ok(), report.lost_particles > 0, report.iterations,
                            report.round_off_stops};
    };
    advance_with_cuts<D>(h, spec_.solver.implicit.max_step_cuts, sim_, totals_, step_size_, attempt,
                         [&](double sub, int cuts) { fail(report, sub, cuts); });
  }
  void after_step() {}

  /// history.csv: Newton's iterations and the step cuts since the previous row (per step when
  /// every step is recorded), the residual norm at the end of the last Newton solve, and the last
  /// step's displacement of each output.node_probes node; a dynamic particle-Newmark run adds the
  /// equilibrium defect's work since the start (StepReport::defect_work). Values: called once per row.
  [[nodiscard]] std::vector<std::string> history_columns() const {
    std::vector<std::string> columns = solver_history_columns<D>(spec_);
    for (const FeBodySpec& body : spec_.fe_bodies)
      for (const char* what : {"_kinetic_energy", "_strain_energy"}) columns.push_back(body.name + what);
    if (audits_defect()) columns.emplace_back("equilibrium_defect_work");
    return columns;
  }
  [[nodiscard]] std::vector<double> history_values() {
    std::vector<double> row = solver_history_values(totals_, marks_);
    const Eigen::VectorXd& u = stepper_->last_increment();
    for (const ProbeWeights& probe : probes_)
      for (int a = 0; a < D; ++a) {
        double value = 0.0;
        for (std::size_t k = 0; k < probe.nodes.size() && u.size() > 0; ++k)
          value += probe.weights[k] * u[probe.nodes[k] * D + a];
        row.push_back(value);
      }
    for (std::size_t b = 0; b < spec_.fe_bodies.size(); ++b) {
      const auto [kinetic, strain] = fe_body_energies(static_cast<int>(b));
      row.push_back(kinetic), row.push_back(strain);
    }
    if (audits_defect()) row.push_back(defect_work_);
    return row;
  }

  /// The FE bodies' kinetic and strain energy and the work gravity did on them: the run adds them
  /// to history.csv's totals and the energy guard's balance (run/run_loop.hpp).
  [[nodiscard]] OtherBodiesEnergy other_bodies_energy() const {
    OtherBodiesEnergy e;
    for (std::size_t b = 0; b < spec_.fe_bodies.size(); ++b) {
      const auto [kinetic, strain] = fe_body_energies(static_cast<int>(b));
      e.kinetic += kinetic, e.strain += strain;
    }
    e.external_work = fe_external_work_;
    return e;
  }

  /// The element mesh (fixed: the grid is reset every step), shown beside the particles.
  void write_static_outputs(const std::filesystem::path& dir, std::string& part) const {
    part = "mesh.vtu";
    mesh::write_mesh_vtu<D>(dir / part, mesh_);
  }

  /// FE bodies: their elements at every particle output (fem/fe_output.hpp), "" without any.
  [[nodiscard]] std::string frame_part_prefix() const { return spec_.fe_bodies.empty() ? "" : "fe_bodies_"; }
  void write_frame(const std::filesystem::path& file) const {
    fem::write_fe_bodies_vtu<E>(file, mesh_, stepper_->fe_bodies());
  }

  /// The checkpoint's solver state: the particle accelerations a^n and host elements (by storage
  /// index; the implicit run does not reorder particles), the totals and the adaptive step.
  void save(RunCounters& c) const {
    std::vector<double> acceleration, element;
    for (const auto& a : state_.acceleration) acceleration.insert(acceleration.end(), a.data(), a.data() + D);
    for (Index e : state_.element) element.push_back(static_cast<double>(e));
    c.solver_state["acceleration"] = std::move(acceleration);
    c.solver_state["element"] = std::move(element);
    save_run_totals(c, totals_, marks_, step_size_);
    std::vector<double> reactions;  // (dof, force) pairs of the moving conditions
    for (const auto& [dof, force] : stepper_->reactions())
      reactions.insert(reactions.end(), {static_cast<double>(dof), force});
    c.solver_state["boundary_reactions"] = std::move(reactions);
    c.solver_state["equilibrium_defect_work"] = {defect_work_};
    if (spec_.fe_bodies.empty()) return;
    const auto& fe = stepper_->fe_bodies();
    std::vector<double> nodes, gauss;  // u, v, a per node; F per Gauss point (row-major)
    for (const auto* field : {&fe.displacement, &fe.velocity, &fe.acceleration})
      for (const auto& x : *field) nodes.insert(nodes.end(), x.data(), x.data() + D);
    for (const auto& F : fe.F)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) gauss.push_back(F(i, j));
    c.solver_state["fe_nodes"] = std::move(nodes);
    c.solver_state["fe_gauss_F"] = std::move(gauss);
    c.solver_state["fe_external_work"] = {fe_external_work_};
  }
  /// Throws InputError when the checkpoint is not an implicit run's of these particles.
  void restore(const RunCounters& c) {
    const std::size_t n = sim_.particles.size();
    const std::string expected = "the implicit solver's state of " + std::to_string(n) +
                                 " particles (the checkpoint is not an implicit run's of this input)";
    const auto& acceleration = checkpoint_array(c, "acceleration", n * D, expected);
    const auto& element = checkpoint_array(c, "element", n, expected);
    restore_run_totals(c, totals_, marks_, step_size_, expected);
    state_.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      for (int a = 0; a < D; ++a)
        state_.acceleration[p][a] = acceleration[p * D + static_cast<std::size_t>(a)];
      state_.element[p] = static_cast<Index>(element[p]);
    }
    std::map<Index, double> reactions;
    if (const auto it = c.solver_state.find("boundary_reactions"); it != c.solver_state.end())
      for (std::size_t k = 0; k + 1 < it->second.size(); k += 2)
        reactions[static_cast<Index>(it->second[k])] = it->second[k + 1];
    stepper_->set_reactions(std::move(reactions));
    if (const auto it = c.solver_state.find("equilibrium_defect_work");
        it != c.solver_state.end() && !it->second.empty())
      defect_work_ = it->second[0];
    stepper_->set_gravity_at_start(gravity_at(sim_.time));
    previous_x_ = sim_.particles.x;
    if (spec_.fe_bodies.empty()) return;
    auto& fe = stepper_->fe_bodies();
    const std::size_t node_values = fe.displacement.size() * D;
    const auto& nodes = checkpoint_array(c, "fe_nodes", 3 * node_values, expected);
    const auto& gauss = checkpoint_array(c, "fe_gauss_F", fe.F.size() * D * D, expected);
    std::size_t k = 0;
    for (auto* field : {&fe.displacement, &fe.velocity, &fe.acceleration})
      for (auto& x : *field)
        for (int a = 0; a < D; ++a) x[a] = nodes[k++];
    k = 0;
    for (auto& F : fe.F)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) F(i, j) = gauss[k++];
    stepper_->restore_reference_nodes();
    fe_external_work_ = checkpoint_array(c, "fe_external_work", 1, expected)[0];
  }

  void add_facts(RunFacts& facts) const {
    const auto& ls = stepper_->linear_solver().stats();
    nlohmann::json s;
    s["formulation"] = spec_.solver.kind == SolverKind::ImplicitUl
                           ? "Iaconeta 2017 updated-Lagrangian MPM (Newmark at the grid nodes)"
                           : "Aulisa & Capodaglio particle-Newmark MPM";
    s["analysis"] = spec_.solver.implicit.static_analysis ? "static" : "dynamic";
    s["element"] = E::kName;
    s["mesh_elements"] = mesh_.element_count();
    s["mesh_nodes"] = mesh_.node_count();
    s["newton_iterations"] = totals_.newton_iterations;
    s["average_newton_iterations"] = totals_.steps > 0 ? static_cast<double>(totals_.newton_iterations) /
                                                             static_cast<double>(totals_.steps)
                                                       : 0.0;
    s["max_newton_iterations_in_a_step"] = totals_.max_iterations_in_a_step;
    s["step_cuts"] = totals_.step_cuts;
    s["newton_round_off_stops"] = totals_.newton_round_off_stops;
    if (spec_.solver.implicit.adaptive.enabled) s["adaptive_dt_at_end"] = step_size_.current();
    s["linear_solver"] = std::string(stepper_->linear_solver().name());
    s["assembly_seconds"] = totals_.assembly_seconds;
    s["factorization_seconds"] = ls.analyze_seconds + ls.factorize_seconds;
    s["solve_seconds"] = ls.solve_seconds;
    s["symbolic_analyses"] = ls.analyses;
    s["factorizations"] = ls.factorizations;
    s["krylov_iterations"] = ls.krylov_iterations;
    if (!spec_.fe_bodies.empty()) {
      const auto& fe = stepper_->fe_bodies();
      s["fe_elements"] = fe.element_count();
      s["fe_gauss_points"] = fe.F.size();
      s["fe_inertia"] =
          spec_.fe_bodies[0].unit_inertia_density ? "unit density (the authors' code, A2)" : "physical";
    }
    facts.implicit = std::move(s);
  }

 private:
  static Spec without_conditions(Spec spec) {
    spec.conditions.clear();  // mesh-boundary conditions: the stepper's, not the explicit grid's
    return spec;
  }
  static std::vector<ImplicitMaterial> implicit_materials(const Simulation<D>& sim) {
    std::vector<ImplicitMaterial> out;
    for (const Material& m : sim.materials) out.emplace_back(m);  // the reader allows no other models
    return out;
  }

  /// The elements of fe_bodies[k]: its element set, or those whose centre lies in its region;
  /// throws InputError when there are none.
  std::vector<Index> fe_body_elements(std::size_t k) const {
    const FeBodySpec& b = spec_.fe_bodies[k];
    const std::string path = "fe_bodies[" + std::to_string(k) + "]";
    if (!b.elements.empty())
      return named_boundary(mesh_.element_sets, b.elements, path + ".elements",
                            "an element set of the mesh (a Gmsh physical group of dimension dim)");
    std::vector<Index> out;
    for (Index e = 0; e < mesh_.element_count(); ++e) {
      Vec<D> centre = Vec<D>::Zero();
      for (const Index n : mesh_.element_nodes(e)) centre += mesh_.nodes[static_cast<std::size_t>(n)];
      centre /= static_cast<double>(mesh_.nodes_per_element);
      bool inside = true;
      for (int a = 0; a < D; ++a)
        inside = inside && centre[a] >= b.region_min[a] && centre[a] <= b.region_max[a];
      if (inside) out.push_back(e);
    }
    if (out.empty())
      throw InputError(
          {{path + ".region", "the box given", "a box holding the centre of at least one mesh element"}});
    return out;
  }

  fem::FeBodies<E> fe_bodies() const {
    if (spec_.fe_bodies.empty()) return {};
    std::vector<fem::FeBodyDefinition> bodies;
    for (std::size_t k = 0; k < spec_.fe_bodies.size(); ++k) {
      const FeBodySpec& b = spec_.fe_bodies[k];
      fem::FeBodyDefinition d;
      d.elements = fe_body_elements(k);
      d.material = b.material;
      d.density = spec_.materials[static_cast<std::size_t>(b.material)].density;
      d.inertia_density = b.unit_inertia_density ? 1.0 : d.density;
      d.gravity = b.gravity;
      bodies.push_back(std::move(d));
    }
    return fem::FeBodies<E>(mesh_, bodies);
  }

  /// FE nodes that also belong to a background element (the interface Γ).
  std::vector<Index> interface_nodes(const fem::FeBodies<E>& fe) const {
    std::vector<char> background(static_cast<std::size_t>(mesh_.node_count()), 0);
    for (Index e = 0; e < mesh_.element_count(); ++e)
      if (fe.element_mask()[static_cast<std::size_t>(e)] == 0)
        for (const Index n : mesh_.element_nodes(e)) background[static_cast<std::size_t>(n)] = 1;
    std::vector<Index> out;
    for (Index n = 0; n < mesh_.node_count(); ++n)
      if (background[static_cast<std::size_t>(n)] != 0 && fe.node_mask()[static_cast<std::size_t>(n)] != 0)
        out.push_back(n);
    return out;
  }

  /// C_c (fe_bodies[k].interface_receding) on every face of a background element whose nodes all
  /// belong to body k's elements: the interface Γ_a of the receding correction (§5).
  void add_interface_receding(const fem::FeBodies<E>& fe,
                              std::map<std::pair<Index, int>, double>& receding) const {
    std::map<int, double> body_receding;  // C_c per FE body with interface_receding > 0
    for (std::size_t b = 0; b < spec_.fe_bodies.size(); ++b)
      if (spec_.fe_bodies[b].interface_receding > 0)
        body_receding.emplace(static_cast<int>(b), spec_.fe_bodies[b].interface_receding);
    if (body_receding.empty()) return;
    std::vector<int> node_body(static_cast<std::size_t>(mesh_.node_count()), -1);
    for (Index k = 0; k < fe.element_count(); ++k)
      for (const Index n : mesh_.element_nodes(fe.mesh_element(k)))
        node_body[static_cast<std::size_t>(n)] = fe.body_of(k);
    for (Index e = 0; e < mesh_.element_count(); ++e) {
      if (fe.element_mask()[static_cast<std::size_t>(e)] != 0) continue;
      const auto nodes = mesh_.element_nodes(e);
      for (int f = 0; f < E::kFaces; ++f) {
        const auto face = E::faces()[static_cast<std::size_t>(f)];
        const int body = node_body[static_cast<std::size_t>(nodes[static_cast<std::size_t>(face[0])])];
        bool shared = body >= 0;
        for (const int local : face)
          shared =
              shared && node_body[static_cast<std::size_t>(nodes[static_cast<std::size_t>(local)])] == body;
        if (shared)
          if (const auto it = body_receding.find(body); it != body_receding.end())
            receding[{e, f}] = it->second;
      }
    }
  }

  /// Throws InputError naming the body when a particle lies inside an FE body's element (§4: the
  /// FE mesh carries the background grid; no particle may be in it).
  void check_particles_outside(const fem::FeBodies<E>& fe) const {
    mesh::PointLocator<D> all(mesh_, mesh_.nodes), background(mesh_, mesh_.nodes);
    background.exclude(fe.element_mask());
    for (std::size_t p = 0; p < sim_.particles.size(); ++p) {
      const Vec<D>& x = sim_.particles.x[p];
      if (background.locate(x) || !all.locate(x)) continue;
      const auto b = static_cast<std::size_t>(sim_.particles.body[p]);
      throw InputError(
          {{"bodies[" + std::to_string(b) + "].shape", "a particle at " + vec_text(x),
            "a body outside the elements of the fe_bodies (a particle can not be inside an FE body)"}});
    }
  }
  static std::string vec_text(const Vec<D>& x) {
    std::ostringstream s;
    s << '(' << x[0];
    for (int a = 1; a < D; ++a) s << ", " << x[a];
    s << ')';
    return s.str();
  }

  /// Calls visit(g, N, nodes) for every Gauss point g of the FE elements of body b (every body with
  /// b < 0): N the shape values at g, nodes its element's node ids.
  template <class Visit>
  void for_each_fe_gauss_point(int b, Visit&& visit) const {
    const auto& fe = stepper_->fe_bodies();
    const auto& rule = fem::fe_gauss_rule<E>();
    const auto per = static_cast<Index>(rule.points.size());
    for (Index k = 0; k < fe.element_count(); ++k) {
      if (b >= 0 && fe.body_of(k) != b) continue;
      const auto nodes = mesh_.element_nodes(fe.mesh_element(k));
      const auto variant = mesh_.element_variant(fe.mesh_element(k));
      for (Index i = 0; i < per; ++i)
        visit(static_cast<std::size_t>(k * per + i),
              E::values(rule.points[static_cast<std::size_t>(i)], variant), nodes);
    }
  }
  /// sum_I N_I f_I over an element's nodes (f: a nodal field, or a difference of two).
  template <class Field>
  static Vec<D> interpolate(const Eigen::Matrix<double, E::kNodes, 1>& N, std::span<const Index> nodes,
                            Field&& f) {
    Vec<D> value = Vec<D>::Zero();
    for (int I = 0; I < E::kNodes; ++I)
      value += N[I] * f(static_cast<std::size_t>(nodes[static_cast<std::size_t>(I)]));
    return value;
  }

  /// Kinetic energy 1/2 sum_g m_g |sum_I N_I v_I|^2 (the consistent mass) and strain energy
  /// sum_g V0_g W(F_g) of FE body b (1/2 sigma : eps with kinematics "small": plane strain's
  /// sigma_zz does no work, eps_zz = 0).
  [[nodiscard]] std::pair<double, double> fe_body_energies(int b) const {
    const auto& fe = stepper_->fe_bodies();
    double kinetic = 0.0, strain = 0.0;
    for_each_fe_gauss_point(b, [&](std::size_t g, const auto& N, std::span<const Index> nodes) {
      kinetic += 0.5 * fe.mass[g] *
                 interpolate(N, nodes, [&](std::size_t n) { return fe.velocity[n]; }).squaredNorm();
      if (spec_.solver.implicit.small_strain) {  // Hooke's energy 1/2 sigma : eps, as the residual
        const Mat<D> eps = 0.5 * (fe.F[g] + fe.F[g].transpose()) - Mat<D>::Identity();
        strain += fe.volume0[g] * 0.5 * fe.stress[g].cwiseProduct(eps).sum();
        return;
      }
      strain += fe.volume0[g] * std::visit(
                                    [&](const auto& model) {
                                      if constexpr (requires { std::decay_t<decltype(model)>::state_size; })
                                        return 0.0;  // plastic models are refused for FE bodies
                                      else
                                        return model.template energy_density<D>(fe.F[g]);
                                    },
                                    sim_.materials[static_cast<std::size_t>(fe.material[g])]);
    });
    return {kinetic, strain};
  }

  /// The work of gravity b on the FE bodies over the step just taken, sum_g rho V0_g b . du_g
  /// (du_g interpolated from the nodes at Gauss point g; the residual's body force m_g s_g b).
  [[nodiscard]] double fe_gravity_work(const Vec<D>& b) const {
    const auto& fe = stepper_->fe_bodies();
    double work = 0.0;
    for_each_fe_gauss_point(-1, [&](std::size_t g, const auto& N, std::span<const Index> nodes) {
      if (fe.body_force_scale[g] == 0.0) return;
      const Vec<D> du = interpolate(
          N, nodes, [&](std::size_t n) -> Vec<D> { return fe.displacement[n] - fe_displacement_before_[n]; });
      work += fe.mass[g] * fe.body_force_scale[g] * b.dot(du);
    });
    return work;
  }

  [[nodiscard]] Vec<D> gravity_at(double t) const { return implicit::gravity_at<D>(spec_, t); }

  /// The (element, face, load index) of every face of the loads.tractions boundaries; throws
  /// InputError naming the load when the mesh has no such boundary.
  void collect_loaded_faces() {
    for (std::size_t k = 0; k < spec_.loads.tractions.size(); ++k) {
      const auto& faces = named_boundary(mesh_.boundary_faces, spec_.loads.tractions[k].boundary,
                                         "loads.tractions[" + std::to_string(k) + "].boundary");
      for (const auto& [element, face] : faces) loaded_faces_.push_back({element, face, k});
    }
  }

  /// The surface loads at time t, one per loaded face.
  [[nodiscard]] std::vector<FaceLoad<D>> face_loads_at(double t) const {
    std::vector<FaceLoad<D>> out;
    out.reserve(loaded_faces_.size());
    for (const auto& [element, face, k] : loaded_faces_) {
      const SurfaceLoadSpec& spec = spec_.loads.tractions[k];
      FaceLoad<D> load;
      load.element = element;
      load.face = face;
      load.follower = spec.pressure.has_value();
      if (spec.pressure) load.pressure = (*spec.pressure)(t);
      for (int a = 0; a < D; ++a)
        if (const auto& component = spec.traction[static_cast<std::size_t>(a)])
          load.traction[a] = (*component)(t);
      out.push_back(load);
    }
    return out;
  }

  /// The displacement of each "velocity" boundary dof over [t0, t1]: the integral of its velocity
  /// (exact for a piecewise-linear table). A later condition on the same dof overrides an earlier one.
  [[nodiscard]] std::vector<std::pair<Index, double>> prescribed_increments(double t0, double t1) const {
    std::vector<std::pair<Index, double>> out;
    out.reserve(moving_dofs_.size());
    for (const auto& [dof, velocity] : moving_dofs_)
      out.emplace_back(dof, velocity->integral(t1) - velocity->integral(t0));
    return out;
  }

  [[noreturn]] void fail(const StepReport& report, double sub, int cuts) const {
    std::ostringstream what;
    if (report.lost_particles > 0) {
      what << report.lost_particles << " particle(s) left the mesh (Aulisa & Capodaglio assume none does)";
      throw NumericalFailure(sim_.step + 1, sim_.time, "particles", what.str());
    }
    what << "Newton did not converge (" << report.newton.message << ") with dt = " << sub << " after " << cuts
         << " step cut(s); residual norms:";
    for (const auto& it : report.newton.history) what << ' ' << it.residual_norm;
    throw NumericalFailure(sim_.step + 1, sim_.time, "Newton iteration", what.str());
  }

  const Spec& spec_;
  Simulation<D> sim_;
  mesh::Mesh<D> mesh_;
  std::optional<ParticleNewmarkStepper<E, ImplicitMaterial>> stepper_;
  ImplicitParticleState<D> state_;
  std::vector<Vec<D>> previous_x_;
  // Gravity's work on the FE bodies (FE bodies with "gravity": true only), and their nodal
  // displacement at the start of the step it is summed over.
  bool fe_takes_gravity_ = false;
  double fe_external_work_ = 0.0;
  double defect_work_ = 0.0;  // the sum of StepReport::defect_work (history.csv equilibrium_defect_work)
  /// A dynamic particle-Newmark run (Aulisa & Capodaglio) writes the equilibrium defect's work.
  [[nodiscard]] bool audits_defect() const {
    return spec_.solver.kind != SolverKind::ImplicitUl && !spec_.solver.implicit.static_analysis;
  }
  std::vector<Vec<D>> fe_displacement_before_;
  ImplicitTotals totals_;
  HistoryMarks marks_;
  /// An output.node_probes entry: the nodal displacement it reads is sum_k weights[k] u~(nodes[k]).
  struct ProbeWeights {
    std::vector<Index> nodes;
    std::vector<double> weights;
  };
  std::vector<ProbeWeights> probes_;  // output.node_probes
  /// output.node_probes: on a Lagrange mesh the node nearest each position (ties: the lowest index),
  /// as particle probes; on a B-spline patch, whose nodes are control points off the body, the
  /// field at the position (sum_I N_I(x) u~_I over the element holding it).
  void set_node_probes(const Spec& spec) {
    if constexpr (E::kShape == mesh::ElementShape::BSpline2) {
      const mesh::PointLocator<D> locator(mesh_, mesh_.nodes);
      for (std::size_t k = 0; k < spec.output.node_probes.size(); ++k) {
        Vec<D> x;
        for (int a = 0; a < D; ++a) x[a] = spec.output.node_probes[k].position[static_cast<std::size_t>(a)];
        const auto at = locator.locate(x);
        if (!at)
          throw InputError({{"output.node_probes[" + std::to_string(k) + "].position", vec_text(x),
                             "a point of the mesh"}});
        const auto ids = mesh_.element_nodes(at->element);
        const auto N = E::values(at->xi, mesh_.element_variant(at->element));
        ProbeWeights probe;
        for (int I = 0; I < E::kNodes; ++I)
          probe.nodes.push_back(ids[static_cast<std::size_t>(I)]), probe.weights.push_back(N[I]);
        probes_.push_back(std::move(probe));
      }
    } else {
      for (long node : probe_particle_ids<D>(mesh_.nodes, spec.output.node_probes))
        probes_.push_back({{static_cast<Index>(node)}, {1.0}});
    }
  }
  std::vector<std::pair<Index, const TimeFunction*>> moving_dofs_;  // "velocity" conditions (spec_'s)
  struct LoadedFace {
    Index element;
    int face;
    std::size_t load;  // index into spec_.loads.tractions
  };
  std::vector<LoadedFace> loaded_faces_;
  NewtonResult last_newton_;  // of the last Newton solve (its residual history)
  StepSizeControl step_size_;
};

}  // namespace matpoint::implicit
