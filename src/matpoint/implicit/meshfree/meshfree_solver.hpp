// The Galerkin meshfree method (Iaconeta et al. 2017 §4.2, Algorithm 2; solver.basis "mls" or "lme"
// with solver.type "implicit_ul") as the shared run loop sees it (run/run_loop.hpp lists the
// interface). The input's mesh only generates the body: its nodes under the particles (those of the
// elements that hold a particle at the start) become the Lagrangian nodes, the particles the
// integration points; then the mesh is discarded, as in the paper. The steps are MeshfreeStepper's;
// this adapter adds what implicit_run_common.hpp shares with the MPMs (step cutting, gravity, the
// history columns, the totals) and:
//   - fixed and slip conditions on the body's nodes of the named boundaries, held at du = 0;
//   - walls: a condition whose boundary is a flat face of the mesh's hull (a structured mesh's sides,
//     a flat Gmsh group on the hull) holds the whole plane, as the MPMs' grid does. The mesh is gone,
//     so a node that reaches the plane (at a step's start, at or beyond it) takes the condition from
//     then on (fixed: sticks; slip: slides along it). Without this, soil that runs out past the
//     column's footprint (where the mesh had floor nodes but the body none) fell through the floor
//     (examples/soil-column-collapse/gmm-mls.json: points 0.39 m below it at t = 0.9 s). A node that
//     crosses the plane within a step is held where the step left it (at most |v| dt beyond);
//   - one_sided conditions: no node is held; the wall acts on the feet of the points near the body's
//     surface (implicit/one_sided_boundary.hpp, MeshfreeStepper's penalty blocks), so a body can roll
//     on it or lift off (examples/implicit-rolling-disk-incline);
//   - the initial nodal velocity and acceleration by consistent-mass projections of the particles'
//     velocity and of the body force (initial_acceleration "body_force": M a^0 = f_ext - f_int;
//     "zero": a^0 = 0, the MPMs' default);
//   - node probes: the field's displacement over the last step, sum_J N_J(x_I^n) du_J, at the node
//     nearest the probe (MLS does not interpolate nodal values, so the node's own du_I would not do);
//   - the checkpoint's solver/ group: the nodes' positions, velocities and accelerations (the
//     particles carry the rest), so a restart continues the run bit for bit (same thread count);
//   - summary.json's implicit.meshfree: the shape parameters and every repair of §6.5;
//   - with solver.meshfree.delete_failed_points (the authors' code, extraction §6.5): the points
//     that have no usable shape functions at a step's start are deleted from the run (body and
//     particles), their number and mass counted; the energy they carried leaves the balance as a loss.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "matpoint/analysis/probes.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/implicit/implicit_material.hpp"
#include "matpoint/implicit/implicit_run_common.hpp"
#include "matpoint/implicit/meshfree/meshfree_stepper.hpp"
#include "matpoint/mesh/mesh.hpp"
#include "matpoint/mesh/point_locator.hpp"
#include "matpoint/run/run_summary.hpp"

namespace matpoint::implicit {

/// The stepper's options from the input (solver.implicit, solver.meshfree).
template <int D>
MeshfreeStepOptions meshfree_step_options(const Spec& spec) {
  const ImplicitSpec& in = spec.solver.implicit;
  MeshfreeStepOptions o;
  MeshfreeParameters& s = o.shape;
  s.basis = in.basis == ImplicitBasis::Lme ? MeshfreeBasis::Lme : MeshfreeBasis::Mls;
  double h = spec.grid.cell_size[0];
  for (int a = 1; a < D; ++a) h = std::min(h, spec.grid.cell_size[a]);
  s.spacing = in.meshfree.spacing.value_or(h);
  s.radius_factor = in.meshfree.radius_factor;
  s.dilation_factor = in.meshfree.dilation_factor.value_or(in.meshfree.radius_factor / 2);  // R_eff = R / 2
  s.gamma = in.meshfree.gamma;
  s.min_nodes = static_cast<std::size_t>(in.meshfree.min_nodes);
  s.lme_max_nodes = static_cast<std::size_t>(in.meshfree.lme_max_nodes);
  s.mls_weight = in.meshfree.mls_truncated_weight ? MlsWeight::Truncated : MlsWeight::Smooth;
  o.project_history = !in.meshfree.carried_node_history;
  o.newmark = {in.beta, in.gamma};
  o.quasi_static = in.static_analysis;
  o.newton = newton_options(in);
  o.linear = linear_solver_options(in);
  return o;
}

template <int D>
class MeshfreeSolver {
 public:
  /// Throws InputError (nothing written yet) for what only the set-up finds (a particle outside
  /// the mesh, a boundary the mesh does not have).
  MeshfreeSolver(const Spec& spec, const mesh::Mesh<D>& mesh)
      : spec_(spec),
        sim_(build_simulation<D>(without_conditions(spec))),
        options_(meshfree_step_options<D>(spec)),
        stepper_(implicit_materials(sim_), options_),
        step_size_(spec.solver) {
    build_body(mesh);
    one_sided_ =
        OneSidedBoundary<D>(one_sided_nodes(mesh, spec), kMaxOneSidedRounds, body_shape_test<D>(spec));
    wall_stiffness_ = one_sided_stiffness(mesh);
    previous_x_ = sim_.particles.x;
    std::vector<Vec<D>> nodes(body_.node_x.begin(), body_.node_x.end());
    for (long node : probe_particle_ids<D>(nodes, spec.output.node_probes))
      probe_nodes_.push_back(static_cast<std::size_t>(node));
    probe_u_.assign(probe_nodes_.size(), Vec<D>::Zero());
    if (!spec.solver.implicit.static_analysis) initial_nodal_state();
  }
  MeshfreeSolver(const MeshfreeSolver&) = delete;
  MeshfreeSolver& operator=(const MeshfreeSolver&) = delete;

  Simulation<D>& sim() { return sim_; }
  [[nodiscard]] const Simulation<D>& sim() const { return sim_; }
  [[nodiscard]] const MeshfreeBody<D>& body() const { return body_; }
  [[nodiscard]] const ImplicitTotals& totals() const { return totals_; }
  /// Nodes that reached a wall and took its condition so far (see the top of this file).
  [[nodiscard]] std::int64_t nodes_held_by_walls() const { return wall_nodes_; }
  [[nodiscard]] MeshfreeRepairCounts repairs() const {
    MeshfreeRepairCounts r = restored_repairs_;
    return r += stepper_.repairs();
  }
  /// The probes' displacement over the last step (see the top of this file).
  [[nodiscard]] const std::vector<Vec<D>>& probe_displacements() const { return probe_u_; }

  /// An output time one to two steps away is reached in two equal steps, never a full step and a
  /// tiny one (run/run_loop.hpp steps_to_land).
  static constexpr bool kEvenStepsToLand = true;
  /// The energy guard after every step (run/energy_guard.hpp): a step costs a Newton solve.
  static constexpr bool kCheckEnergyEveryStep = true;

  [[nodiscard]] double time_step() const { return step_size_.next(sim_.time); }

  /// Advances by h: one Newton solve, or after a failure 2, 4, ... sub-steps (at most
  /// max_step_cuts halvings); throws NumericalFailure when even the smallest sub-step fails.
  void step(double h) {
    NewtonResult result;
    const auto attempt = [&](double done, double sub) {
      const Vec<D> gravity = gravity_at<D>(spec_, sim_.time + done + sub);  // at the end of the sub-step
      const std::vector<Vec<D>> nodes_before = body_.node_x;
      const double assembly_before = stepper_.assembly_seconds();
      const int round_off_stops_before = stepper_.round_off_stops();
      const int iterations_before = stepper_.newton_iterations();
      if (spec_.solver.implicit.meshfree.delete_failed_points) delete_failed_points();
      hold_nodes_on_walls();
      OneSidedBoundary<D>* walls = nullptr;
      if (!one_sided_.empty()) {
        one_sided_.start_step(sim_.particles, sub);
        walls = &one_sided_;
      }
      result = stepper_.step(body_, sub, gravity, walls, wall_stiffness_);
      totals_.assembly_seconds += stepper_.assembly_seconds() - assembly_before;
      marks_.newton_residual = result.final_residual_norm;
      if (result.converged()) {
        to_particles();
        account_gravity_work<D>(sim_, previous_x_, sub, gravity);
        probe_step(nodes_before);
      }
      return SubStepOutcome{result.converged(), false, stepper_.newton_iterations() - iterations_before,
                            stepper_.round_off_stops() - round_off_stops_before};
    };
    advance_with_cuts<D>(h, spec_.solver.implicit.max_step_cuts, sim_, totals_, step_size_, attempt,
                         [&](double sub, int cuts) { fail(result, sub, cuts); });
  }
  void after_step() {}

  [[nodiscard]] std::vector<std::string> history_columns() const { return solver_history_columns<D>(spec_); }
  [[nodiscard]] std::vector<double> history_values() {
    std::vector<double> row = solver_history_values(totals_, marks_);
    for (const auto& u : probe_u_) row.insert(row.end(), u.data(), u.data() + D);
    return row;
  }

  /// No mesh is kept (the paper discards it after the set-up).
  void write_static_outputs(const std::filesystem::path&, std::string& part) const { part.clear(); }

  /// The checkpoint's solver state: the nodes' x, v, a (3 D values per node), the repairs so far,
  /// the probes' last displacement, the totals and the adaptive step.
  void save(RunCounters& c) const {
    std::vector<double> nodes;
    nodes.reserve(body_.node_x.size() * 3 * D);
    for (std::size_t I = 0; I < body_.node_x.size(); ++I)
      for (const auto* field : {&body_.node_x, &body_.node_v, &body_.node_a})
        nodes.insert(nodes.end(), (*field)[I].data(), (*field)[I].data() + D);
    c.solver_state["meshfree_nodes"] = std::move(nodes);
    const MeshfreeRepairCounts r = repairs();
    c.solver_state["meshfree_repairs"] = {
        static_cast<double>(r.mls_radius_grown), static_cast<double>(r.mls_shepard),
        static_cast<double>(r.lme_augmented), static_cast<double>(r.lme_nodes_added),
        static_cast<double>(r.failed)};
    std::vector<double> probes;
    for (const auto& u : probe_u_) probes.insert(probes.end(), u.data(), u.data() + D);
    c.solver_state["meshfree_probes"] = std::move(probes);
    c.solver_state["meshfree_deleted_and_idle"] = {static_cast<double>(deleted_points_), deleted_mass_,
                                                   static_cast<double>(r.idle_nodes)};
    std::vector<double> point_a;  // the next step projects it to the nodes (MeshfreeStepper)
    for (const auto& a : body_.point_a) point_a.insert(point_a.end(), a.data(), a.data() + D);
    c.solver_state["meshfree_point_accelerations"] = std::move(point_a);
    save_run_totals(c, totals_, marks_, step_size_);
  }
  /// Throws InputError when the checkpoint is not a meshfree run's of this body.
  void restore(const RunCounters& c) {
    const std::size_t nodes = body_.node_x.size();
    const std::string expected = "the meshfree solver's state of " + std::to_string(nodes) +
                                 " nodes (the checkpoint is not a meshfree run's of this input)";
    const auto& x = checkpoint_array(c, "meshfree_nodes", nodes * 3 * D, expected);
    for (std::size_t I = 0, k = 0; I < nodes; ++I)
      for (auto* field : {&body_.node_x, &body_.node_v, &body_.node_a})
        for (int a = 0; a < D; ++a) (*field)[I][a] = x[k++];
    stepper_.reset_repairs();  // the set-up's projections counted again what the checkpoint holds
    const auto& r = checkpoint_array(c, "meshfree_repairs", 5, expected);
    restored_repairs_ = {static_cast<std::int64_t>(r[0]), static_cast<std::int64_t>(r[1]),
                         static_cast<std::int64_t>(r[2]), static_cast<std::int64_t>(r[3]),
                         static_cast<std::int64_t>(r[4])};
    if (const auto it = c.solver_state.find("meshfree_deleted_and_idle"); it != c.solver_state.end()) {
      const auto& d = checkpoint_array(c, "meshfree_deleted_and_idle", 3, expected);
      deleted_points_ = static_cast<std::int64_t>(d[0]), deleted_mass_ = d[1];
      restored_repairs_.idle_nodes = static_cast<std::int64_t>(d[2]);
    }  // absent: a checkpoint from before these counts existed
    const auto& u = checkpoint_array(c, "meshfree_probes", probe_u_.size() * D, expected);
    for (std::size_t k = 0; k < probe_u_.size(); ++k)
      for (int a = 0; a < D; ++a) probe_u_[k][a] = u[k * D + static_cast<std::size_t>(a)];
    restore_run_totals(c, totals_, marks_, step_size_, expected);
    from_particles();
    // Empty before the first step; absent in a checkpoint from before the projection existed (the
    // nodes' own history goes on).
    body_.point_a.clear();
    const auto it = c.solver_state.find("meshfree_point_accelerations");
    if (it != c.solver_state.end() && !it->second.empty()) {
      const auto& a = checkpoint_array(c, "meshfree_point_accelerations", body_.point_x.size() * D, expected);
      body_.point_a.resize(body_.point_x.size());
      for (std::size_t p = 0; p < body_.point_a.size(); ++p)
        for (int k = 0; k < D; ++k) body_.point_a[p][k] = a[p * D + static_cast<std::size_t>(k)];
    }
    previous_x_ = sim_.particles.x;
  }

  void add_facts(RunFacts& facts) const {
    const auto& ls = stepper_.linear_solver().stats();
    const MeshfreeParameters& shape = options_.shape;
    const bool mls = shape.basis == MeshfreeBasis::Mls;
    nlohmann::json s;
    s["formulation"] = std::string("Iaconeta 2017 Galerkin meshfree method (") + (mls ? "MLS" : "LME") + ")";
    s["analysis"] = spec_.solver.implicit.static_analysis ? "static" : "dynamic";
    s["mesh_nodes"] = body_.node_x.size();
    s["newton_iterations"] = totals_.newton_iterations;
    s["average_newton_iterations"] = totals_.steps > 0 ? static_cast<double>(totals_.newton_iterations) /
                                                             static_cast<double>(totals_.steps)
                                                       : 0.0;
    s["max_newton_iterations_in_a_step"] = totals_.max_iterations_in_a_step;
    s["step_cuts"] = totals_.step_cuts;
    s["newton_round_off_stops"] = totals_.newton_round_off_stops;
    if (spec_.solver.implicit.adaptive.enabled) s["adaptive_dt_at_end"] = step_size_.current();
    s["linear_solver"] = std::string(stepper_.linear_solver().name());
    s["assembly_seconds"] = totals_.assembly_seconds;
    s["factorization_seconds"] = ls.analyze_seconds + ls.factorize_seconds;
    s["solve_seconds"] = ls.solve_seconds;
    s["symbolic_analyses"] = ls.analyses;
    s["factorizations"] = ls.factorizations;
    s["krylov_iterations"] = ls.krylov_iterations;
    nlohmann::json m;
    m["basis"] = mls ? "mls" : "lme";
    m["nodes"] = body_.node_x.size();
    m["spacing"] = shape.spacing;
    m["radius"] = shape.radius();
    if (mls) m["dilation"] = shape.dilation();
    if (mls) m["weight"] = shape.mls_weight == MlsWeight::Smooth ? "smooth" : "truncated";
    m["node_history"] = options_.project_history ? "projected" : "carried";
    if (!mls) m["gamma"] = shape.gamma;
    m["assembly_colours"] = stepper_.colours();
    const MeshfreeRepairCounts r = repairs();
    m["repairs"] = {{"mls_radius_grown", r.mls_radius_grown},
                    {"mls_shepard", r.mls_shepard},
                    {"lme_augmented", r.lme_augmented},
                    {"lme_nodes_added", r.lme_nodes_added},
                    {"failed", r.failed},
                    {"idle_nodes", r.idle_nodes},
                    {"nodes_held_by_walls", wall_nodes_},
                    {"points_deleted", deleted_points_},
                    {"mass_deleted", deleted_mass_}};
    s["meshfree"] = std::move(m);
    facts.implicit = std::move(s);
  }

 private:
  static Spec without_conditions(Spec spec) {
    spec.conditions.clear();  // mesh-boundary conditions: the nodes', not the explicit grid's
    return spec;
  }
  static std::vector<ImplicitMaterial> implicit_materials(const Simulation<D>& sim) {
    std::vector<ImplicitMaterial> out;
    for (const Material& m : sim.materials) out.emplace_back(m);  // the reader allows no other models
    return out;
  }

  /// The nodes of the elements that hold a particle, and the particles as points; the fixed dofs.
  void build_body(const mesh::Mesh<D>& mesh) {
    const mesh::PointLocator<D> locator(mesh, mesh.nodes);
    std::vector<Index> body_node(static_cast<std::size_t>(mesh.node_count()), -1);
    const ParticleSet<D>& ps = sim_.particles;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const auto location = locator.locate(ps.x[p]);
      if (!location) {
        std::ostringstream where;
        where << "(" << ps.x[p].transpose() << ")";
        throw InputError({{"bodies", where.str(),
                           "particles inside the mesh (its nodes under the particles become the meshfree "
                           "body's nodes)"}});
      }
      for (Index n : mesh.element_nodes(location->element)) body_node[static_cast<std::size_t>(n)] = 0;
    }
    for (std::size_t n = 0; n < body_node.size(); ++n)
      if (body_node[n] == 0) {
        body_node[n] = static_cast<Index>(body_.node_x.size());
        body_.node_x.push_back(mesh.nodes[n]);
      }
    body_.node_v.assign(body_.node_x.size(), Vec<D>::Zero());
    body_.node_a = body_.node_v;
    body_.fixed.assign(body_.node_x.size() * D, 0);
    for (std::size_t k = 0; k < spec_.conditions.size(); ++k) {
      const VelocityConditionSpec& c = spec_.conditions[k];  // fixed or slip (the reader refuses others)
      if (c.one_sided) continue;  // a wall on the points' feet (one_sided_boundary.hpp), no node held
      const auto& nodes = boundary_nodes(mesh, c, k);
      for (Index n : nodes) {
        const Index I = body_node[static_cast<std::size_t>(n)];
        if (I < 0) continue;  // not under the body
        hold_node(static_cast<std::size_t>(I), c);
      }
      if (auto wall = hull_plane(mesh, nodes)) {
        wall->condition = k;
        walls_.push_back(*wall);
      }
    }
    from_particles();
  }

  /// The one-sided walls' penalty, kFootPenalty (lambda + 2 mu)_max L^(D-2) with L the mesh's
  /// first element's extent (the MPM stepper takes each foot's host element).
  double one_sided_stiffness(const mesh::Mesh<D>& mesh) const {
    double modulus = 0.0;
    for (const ImplicitMaterial& m : implicit_materials(sim_))
      modulus = std::max(modulus, m.lambda + 2.0 * m.mu);
    Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    if (mesh.element_count() > 0)
      for (const Index n : mesh.element_nodes(0))
        lo = lo.cwiseMin(mesh.nodes[static_cast<std::size_t>(n)]),
        hi = hi.cwiseMax(mesh.nodes[static_cast<std::size_t>(n)]);
    const double extent = mesh.element_count() > 0 ? (hi - lo).maxCoeff() : 1.0;
    return kFootPenalty * modulus * std::pow(extent, D - 2);
  }

  /// Holds node I's dofs that condition c fixes; true when one of them was free.
  bool hold_node(std::size_t I, const VelocityConditionSpec& c) {
    bool newly = false;
    for (int a = 0; a < D; ++a)
      if (c.kind == ConditionKind::Fixed || a == c.normal_axis) {
        char& held = body_.fixed[I * D + static_cast<std::size_t>(a)];
        newly = newly || held == 0;
        held = 1;
      }
    return newly;
  }

  /// A plane of the mesh's hull that holds a boundary's nodes: x_axis = position, the mesh on the
  /// side `inward` (+1: larger coordinates) of it.
  struct Wall {
    int axis = 0;
    double position = 0.0;
    double inward = 1.0;
    std::size_t condition = 0;
  };
  /// The wall of a boundary whose nodes all lie on one face of the mesh's bounding box, if any.
  static std::optional<Wall> hull_plane(const mesh::Mesh<D>& mesh, const std::vector<Index>& nodes) {
    if (nodes.empty()) return std::nullopt;
    Vec<D> lo = mesh.nodes.front(), hi = lo;
    for (const auto& x : mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    for (int a = 0; a < D; ++a) {
      const double tol = 1e-9 * (hi[a] - lo[a]);
      for (const double side : {-1.0, 1.0}) {
        const double plane = side < 0 ? lo[a] : hi[a];
        bool flat = true;
        for (Index n : nodes)
          flat = flat && std::abs(mesh.nodes[static_cast<std::size_t>(n)][a] - plane) <= tol;
        if (flat) return Wall{a, plane, -side, 0};
      }
    }
    return std::nullopt;
  }

  /// Walls (see the top of this file): the nodes at or beyond a wall's plane take its condition.
  void hold_nodes_on_walls() {
    for (const Wall& w : walls_) {
      const VelocityConditionSpec& c = spec_.conditions[w.condition];
      for (std::size_t I = 0; I < body_.node_x.size(); ++I) {
        if ((body_.node_x[I][w.axis] - w.position) * w.inward > 0.0) continue;  // inside the mesh
        if (hold_node(I, c)) ++wall_nodes_;
      }
    }
  }

  /// The deletion repair (see the top of this file), before a step's Newton solve.
  void delete_failed_points() {
    std::vector<char> gone;
    if (stepper_.flag_points_without_functions(body_, gone) == 0) return;
    for (std::size_t p = 0; p < gone.size(); ++p)
      if (gone[p]) ++deleted_points_, deleted_mass_ += body_.point_mass[p];
    body_.remove_points(gone);
    remove_particles(sim_.particles, gone);
    keep_unflagged(previous_x_, gone, 1);
  }

  /// The particles' kinematic and material state into the body's points (set-up and restart, where
  /// points may have been deleted before the checkpoint).
  void from_particles() {
    const ParticleSet<D>& ps = sim_.particles;
    body_.point_mass = ps.mass;
    body_.point_volume0 = ps.volume0;
    body_.point_material = ps.material;
    body_.point_x = ps.x;
    body_.point_F = ps.F;
    body_.point_v = ps.v;
    body_.point_stress = ps.stress;
    body_.state_stride = ps.state_stride;
    body_.point_state = ps.state;
  }
  /// A converged step's results into the particles (writers, energies, measures, checkpoints).
  void to_particles() {
    ParticleSet<D>& ps = sim_.particles;
    ps.x = body_.point_x;
    ps.F = body_.point_F;
    ps.v = body_.point_v;
    ps.stress = body_.point_stress;
    if constexpr (D == 2) ps.stress_zz = body_.point_stress_zz;
    ps.state = body_.point_state;
  }

  /// v^0 and a^0 at the nodes (see the top of this file).
  void initial_nodal_state() {
    const ParticleSet<D>& ps = sim_.particles;
    bool moving = false;
    for (const auto& v : ps.v) moving = moving || v.squaredNorm() > 0.0;
    if (moving && !stepper_.project_to_nodes(body_, ps.v, false, body_.node_v))
      throw InputError({{"bodies", "velocity",
                         "an initial velocity the meshfree nodes can take (its projection to them failed)"}});
    if (!spec_.solver.implicit.initial_acceleration_from_body_force) return;
    const std::vector<Vec<D>> b(ps.size(), gravity_at<D>(spec_, 0.0));
    if (!stepper_.project_to_nodes(body_, b, true, body_.node_a))
      throw InputError({{"solver.implicit.initial_acceleration", "\"body_force\"",
                         "\"zero\" (the meshfree projection of the body force to the nodes failed)"}});
  }

  /// The probes' field displacement over the converged step from the step-start nodes.
  void probe_step(const std::vector<Vec<D>>& nodes_before) {
    if (probe_nodes_.empty()) return;
    std::vector<Vec<D>> x;
    for (std::size_t I : probe_nodes_) x.push_back(nodes_before[I]);
    MeshfreeStencils<D> st;
    build_meshfree_stencils<D>(x, nodes_before, options_.shape, st);
    const Eigen::VectorXd& du = stepper_.last_increment();
    for (std::size_t k = 0; k < probe_nodes_.size(); ++k) {
      probe_u_[k].setZero();
      for (auto j = st.offset[k]; j < st.offset[k + 1]; ++j)
        probe_u_[k] += st.N[static_cast<std::size_t>(j)] * du.segment<D>(static_cast<Index>(st.node[j]) * D);
    }
  }

  [[noreturn]] void fail(const NewtonResult& result, double sub, int cuts) const {
    std::ostringstream what;
    what << "Newton did not converge (" << result.message << ") with dt = " << sub << " after " << cuts
         << " step cut(s); residual norms:";
    for (const auto& it : result.history) what << ' ' << it.residual_norm;
    if (const Index p = stepper_.non_finite_point(); p >= 0) {
      const auto q = static_cast<std::size_t>(p);
      what << "; the first non-finite residual was particle " << sim_.particles.id[q] << "'s (x = ("
           << body_.point_x[q].transpose() << "), det F = " << body_.point_F[q].determinant() << ")";
    }
    throw NumericalFailure(sim_.step + 1, sim_.time, "Newton iteration", what.str());
  }

  const Spec& spec_;
  Simulation<D> sim_;
  MeshfreeStepOptions options_;
  MeshfreeStepper<D, ImplicitMaterial> stepper_;
  MeshfreeBody<D> body_;
  std::vector<Vec<D>> previous_x_;
  ImplicitTotals totals_;
  HistoryMarks marks_;
  MeshfreeRepairCounts restored_repairs_;  // of the sessions before a restart
  std::vector<Wall> walls_;
  OneSidedBoundary<D> one_sided_;  // one_sided conditions: walls on the points' feet
  double wall_stiffness_ = 0.0;
  std::int64_t wall_nodes_ = 0;      // nodes that reached a wall and took its condition
  std::int64_t deleted_points_ = 0;  // delete_failed_points: points deleted so far, and their mass
  double deleted_mass_ = 0.0;
  std::vector<std::size_t> probe_nodes_;  // output.node_probes: body nodes
  std::vector<Vec<D>> probe_u_;
  StepSizeControl step_size_;
};

}  // namespace matpoint::implicit
