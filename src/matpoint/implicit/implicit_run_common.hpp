// What every implicit run-loop adapter shares, whatever its formulation (implicit_mpm_solver.hpp for
// the MPMs, meshfree/meshfree_solver.hpp for the Galerkin meshfree method): the step-cutting policy,
// gravity with loads.gravity_scale, gravity's work, the history.csv solver columns, the totals of
// summary.json and their place in a checkpoint's solver/ group, and the named mesh boundaries.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/newton.hpp"
#include "matpoint/implicit/one_sided_boundary.hpp"
#include "matpoint/implicit/step_size_control.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/mesh/mesh.hpp"
#include "matpoint/particles/generators.hpp"

namespace matpoint::implicit {

/// Newton's options from solver.implicit.newton (every formulation).
[[nodiscard]] inline NewtonOptions newton_options(const ImplicitSpec& in) {
  NewtonOptions o;
  o.max_iterations = in.max_iterations;
  o.increment_tolerance = in.increment_tolerance;
  o.residual_relative = in.residual_tolerance;
  o.line_search = in.line_search;
  return o;
}

/// The linear solver chosen by solver.implicit.linear_solver (every formulation).
[[nodiscard]] inline LinearSolverOptions linear_solver_options(const ImplicitSpec& in) {
  LinearSolverOptions o;
  switch (in.linear_solver) {
    case LinearSolverChoice::Umfpack:
      o.kind = LinearSolverKind::Umfpack;
      break;
    case LinearSolverChoice::Klu:
      o.kind = LinearSolverKind::Klu;
      break;
    case LinearSolverChoice::BiCgStab:
      o.kind = LinearSolverKind::BicgstabIlut;
      break;
    case LinearSolverChoice::Gmres:
      o.kind = LinearSolverKind::GmresIlut;
      break;
    case LinearSolverChoice::Petsc:
      o.kind = LinearSolverKind::Petsc;
      break;
  }
  return o;
}

/// The run's totals for summary.json (a checkpoint keeps them).
struct ImplicitTotals {
  long steps = 0, newton_iterations = 0, step_cuts = 0, max_iterations_in_a_step = 0;
  double assembly_seconds = 0.0;
  long newton_round_off_stops = 0;  // Newton solves ended by the round-off stop (newton.hpp)
};

/// What history.csv's solver columns need: the totals at the previous row and the last residual.
struct HistoryMarks {
  long newton_iterations = 0, step_cuts = 0;  // ImplicitTotals' at the previous history row
  double newton_residual = 0.0;               // |R| at the end of the last Newton solve
};

/// The non-empty entry `name` of a mesh's named sets (node sets, boundary faces); throws InputError
/// at `path` listing the mesh's names when there is none.
template <class Sets>
const typename Sets::mapped_type& named_boundary(const Sets& sets, const std::string& name,
                                                 const std::string& path,
                                                 const std::string& what = "a boundary of the mesh") {
  const auto it = sets.find(name);
  if (it == sets.end() || it->second.empty()) {
    std::string names;
    for (const auto& entry : sets) names += (names.empty() ? "\"" : ", \"") + entry.first + "\"";
    throw InputError(
        {{path, "\"" + name + "\"", what + ": one of " + (names.empty() ? std::string("(none)") : names)}});
  }
  return it->second;
}

/// The nodes of a named boundary; throws InputError naming the condition when the mesh has none.
template <int D>
const std::vector<Index>& boundary_nodes(const mesh::Mesh<D>& m, const VelocityConditionSpec& c,
                                         std::size_t k) {
  return named_boundary(m.node_sets, c.boundary, "boundary_conditions[" + std::to_string(k) + "].boundary");
}

/// The nodes of the one-sided conditions with their walls (one_sided_boundary.hpp); throws
/// InputError for a boundary that is not a plane at the mesh's edge (the wall needs the body on one
/// side of it).
template <int D>
std::vector<OneSidedNode> one_sided_nodes(const mesh::Mesh<D>& mesh, const Spec& spec) {
  std::vector<OneSidedNode> out;
  for (std::size_t k = 0; k < spec.conditions.size(); ++k) {
    const VelocityConditionSpec& c = spec.conditions[k];
    if (!c.one_sided) continue;
    const auto& nodes = boundary_nodes(mesh, c, k);
    const auto plane = wall_plane<D>(mesh.nodes, nodes);
    const std::string path = "boundary_conditions[" + std::to_string(k) + "]";
    if (!plane)
      throw InputError({{path + ".one_sided", "true",
                         "false: boundary \"" + c.boundary +
                             "\" is not a plane x_i = constant at the mesh's edge (a one-sided wall "
                             "needs the body on one side)"}});
    if (c.kind == ConditionKind::Slip && c.normal_axis != plane->axis)
      throw InputError({{path + ".normal", std::string("\"") + "xyz"[c.normal_axis] + "\"",
                         std::string("\"") + "xyz"[plane->axis] +
                             "\", the wall's normal (a one-sided slip wall holds the normal component)"}});
    for (Index n : nodes) out.push_back({n, *plane, c.kind == ConditionKind::Fixed});
  }
  return out;
}

/// Whether a reference point lies in body k's shape (bodies[k].shape): where the one-sided walls
/// find the bodies' surfaces.
template <int D>
BodyShapeTest<D> body_shape_test(const Spec& spec) {
  return [bodies = spec.bodies](int body, const Vec<D>& x) {
    return body >= 0 && static_cast<std::size_t>(body) < bodies.size() &&
           shape_contains<D>(bodies[static_cast<std::size_t>(body)], x);
  };
}

/// loads.gravity times loads.gravity_scale at time t.
template <int D>
[[nodiscard]] Vec<D> gravity_at(const Spec& spec, double t) {
  Vec<D> g;
  const double scale = spec.loads.gravity_scale(t);
  for (int a = 0; a < D; ++a) g[a] = scale * spec.loads.gravity[a];
  return g;
}

/// Gravity's work sum m g . dx and impulse M g h over a completed sub-step (the energy balance);
/// previous_x becomes the particles' present positions.
template <int D>
void account_gravity_work(Simulation<D>& sim, std::vector<Vec<D>>& previous_x, double h, const Vec<D>& g) {
  double work = 0.0, mass = 0.0;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    mass += sim.particles.mass[p];
    work += sim.particles.mass[p] * g.dot(sim.particles.x[p] - previous_x[p]);
  }
  sim.external_work += work;
  sim.external_impulse += mass * h * g;
  previous_x = sim.particles.x;
}

/// One attempt at a sub-step, as the step-cutting loop sees it.
struct SubStepOutcome {
  bool ok = false;
  bool give_up = false;  // a failure that a smaller step cannot mend (particles lost)
  int iterations = 0;    // Newton iterations of every solve of the attempt
  int round_off_stops = 0;  // solves of the attempt that converged by Newton's round-off stop
};

/// Advances by h through attempt(offset, sub), which tries the sub-step [t + offset, t + offset +
/// sub]: after a failure the sub-step is halved and retried (2, 4, ... sub-steps, at most max_cuts
/// halvings), then fail(sub, cuts) is called (it must throw NumericalFailure). Counts the totals and
/// ends the step: sim's step, time and last_dt, the step-size control's update.
template <int D, class Attempt, class Fail>
void advance_with_cuts(double h, int max_cuts, Simulation<D>& sim, ImplicitTotals& totals,
                       StepSizeControl& step_size, Attempt&& attempt, Fail&& fail) {
  double done = 0.0, sub = h;
  int cuts = 0, most_iterations = 0;
  while (done < h * (1 - 1e-12)) {
    sub = std::min(sub, h - done);
    const SubStepOutcome outcome = attempt(done, sub);
    totals.newton_iterations += outcome.iterations;
    totals.newton_round_off_stops += outcome.round_off_stops;
    totals.max_iterations_in_a_step = std::max<long>(totals.max_iterations_in_a_step, outcome.iterations);
    if (!outcome.ok) {
      if (outcome.give_up || cuts >= max_cuts) fail(sub, cuts);
      ++cuts, ++totals.step_cuts;
      sub *= 0.5;
      continue;
    }
    most_iterations = std::max(most_iterations, outcome.iterations);
    done += sub;
  }
  ++sim.step;
  ++totals.steps;
  sim.time += h;
  sim.last_dt = h;
  step_size.after_step(h, cuts, most_iterations);
}

/// history.csv's solver columns: Newton's iterations and the step cuts since the previous row, the
/// residual norm at the end of the last Newton solve, and each output.node_probes node's
/// displacement over the last step.
template <int D>
[[nodiscard]] std::vector<std::string> solver_history_columns(const Spec& spec) {
  std::vector<std::string> columns{"newton_iterations", "newton_residual", "step_cuts"};
  for (const ProbeSpec& probe : spec.output.node_probes)
    for (int a = 0; a < D; ++a) columns.push_back("node_" + probe.name + "_u" + "xyz"[a]);
  return columns;
}
/// The first three of those values; moves the marks to the totals (called once per row).
[[nodiscard]] inline std::vector<double> solver_history_values(const ImplicitTotals& totals,
                                                               HistoryMarks& marks) {
  std::vector<double> row{static_cast<double>(totals.newton_iterations - marks.newton_iterations),
                          marks.newton_residual, static_cast<double>(totals.step_cuts - marks.step_cuts)};
  marks.newton_iterations = totals.newton_iterations;
  marks.step_cuts = totals.step_cuts;
  return row;
}

/// The totals, history marks and the adaptive step into a checkpoint's solver/ group.
inline void save_run_totals(RunCounters& c, const ImplicitTotals& totals, const HistoryMarks& marks,
                            const StepSizeControl& step_size) {
  c.solver_state["totals"] = {static_cast<double>(totals.steps),
                              static_cast<double>(totals.newton_iterations),
                              static_cast<double>(totals.step_cuts),
                              static_cast<double>(totals.max_iterations_in_a_step), totals.assembly_seconds};
  c.solver_state["history_marks"] = {static_cast<double>(marks.newton_iterations),
                                     static_cast<double>(marks.step_cuts), marks.newton_residual};
  c.solver_state["dt"] = {step_size.current()};
  c.solver_state["round_off_stops"] = {static_cast<double>(totals.newton_round_off_stops)};
}

/// The checkpoint's array solver/`name` of `size` values; throws InputError (--restart) saying what
/// `expected` when it is missing or has another size.
inline const std::vector<double>& checkpoint_array(const RunCounters& c, const std::string& name,
                                                   std::size_t size, const std::string& expected) {
  const auto it = c.solver_state.find(name);
  if (it == c.solver_state.end() || it->second.size() != size)
    throw InputError({{"--restart", "solver/" + name, expected}});
  return it->second;
}

/// save_run_totals' values back.
inline void restore_run_totals(const RunCounters& c, ImplicitTotals& totals, HistoryMarks& marks,
                               StepSizeControl& step_size, const std::string& expected) {
  const auto& t = checkpoint_array(c, "totals", 5, expected);
  const auto& m = checkpoint_array(c, "history_marks", 3, expected);
  totals = {static_cast<long>(t[0]), static_cast<long>(t[1]), static_cast<long>(t[2]),
            static_cast<long>(t[3]), t[4]};
  marks = {static_cast<long>(m[0]), static_cast<long>(m[1]), m[2]};
  // Checkpoints written before 2026-11-28 have no count: it restarts from 0.
  if (const auto it = c.solver_state.find("round_off_stops"); it != c.solver_state.end() && it->second.size() == 1)
    totals.newton_round_off_stops = static_cast<long>(it->second[0]);
  step_size.restore(checkpoint_array(c, "dt", 1, expected)[0]);
}

}  // namespace matpoint::implicit
