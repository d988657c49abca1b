// One time step of the Galerkin meshfree method (Iaconeta et al. 2017 §4.2, Algorithm 2;
// extraction §6.1) on the implicit framework: the nodes of the initial mesh are Lagrangian and keep
// (v, a) history, the material points are the integration points. Per step:
//   (1) every point's cloud and shape functions at x^n (shape/meshfree_stencils.hpp, MLS or LME,
//       with the repairs of §5.3 when asked); the blocks of the sparse assembly are the clouds' dofs;
//   (2) Newton on the nodal increments du (point_residual.hpp; Newmark with the nodal history, or
//       quasi-static), Dirichlet dofs held at du = 0;
//   (3) x_p += sum_I N_I du_I, F_p = H_p F_p^n, the nodes' Newmark update of their coefficients
//       a = c du + c_v v^n + c_a a^n, v = v^n + dt ((1 - gamma) a^n + gamma a), and each node moves
//       with the field at its own position, x_I += sum_J N_J(x_I) du_J.
// Node motion: the paper's Algorithm 2 leaves it implicit (extraction §6.1 writes x_I += du_I). With
// MLS (and LME inside the hull) du_I is a coefficient, not the material's displacement at x_I, and
// moving nodes by it let coefficient oscillations scramble the nodes: in the cohesive column
// (examples/soil-column-collapse/gmm-mls.json) interior nodes reached 100-250 m/s and crossed each
// other within 0.074 s while the points moved by centimetres, fixed floor nodes left the floor
// (the multipliers hold the field at them, not their coefficients), and a fixed node's cloud became
// degenerate. Moving nodes with the field keeps them where the material is, fixed nodes fixed, and is
// the same motion for a translation (partition of unity) or any field that LME or MLS reproduces.
// Node history (our repair, MeshfreeStepOptions::project_history, input solver.meshfree.node_history
// "projected", the default; "carried" is the paper's): once nodes move
// with the field, the coefficients' v_I and a_I describe, on the moved nodes' new functions, a
// velocity field that is no longer the one the step ended with, and every step injects that
// difference. In the MLS column the energy balance then crept up from t = 0.88 s and a cluster of
// points near the slope's crest reached 20 m/s within four steps (t = 0.92 s), at dt = 2e-3 s and
// 1e-3 s alike. So each step starts from v_I, a_I projected from the points' v_p, a_p (the field
// at each point at the end of the previous step) by the consistent mass, as project_to_nodes does
// at the start: the velocity field is the material's, and an L2 projection does not add kinetic
// energy. It costs one more factorisation per step (of the mass matrix, on Newton's pattern).
// Dirichlet conditions (du = 0 on the flagged dofs of the nodes): MLS has no Kronecker-delta
// property, so fixing a node's dofs does not make the field vanish there; with `multipliers` (the
// authors' choice, extraction A14) the field itself is held, sum_J N_J(x_d) du_J,i = 0 at each
// fixed node's position x_d, by one Lagrange multiplier per fixed dof. LME interpolates on the
// hull boundary (weak Kronecker delta), so fixing every node of a boundary face is exact there and
// `multipliers` can be off.
// One-sided walls (implicit/one_sided_boundary.hpp): the feet of the points near the body's surface
// that reach a wall are held by penalties on the point's cloud (assembled with the point's block),
// u(x_f) = sum_J W_J du_J with W_J = N_J(x_p) + grad N_J(x_p) . (x_f - x_p) (the foot moves with
// its point), and the step is solved again while the contact set changes, as in the MPM stepper;
// the walls hold no node.
// No-slip walls hold a foot's tangential displacement at the one that brings it to rest
// (newmark_stop_displacement from the foot's nodal v, a), not at zero: a foot that lands during the
// step was still sliding at its start, and u_t = 0 over a trapezoidal step ends it with its tangential
// velocity reversed. In the rolling disk (examples/implicit-rolling-disk-incline, h = 0.04 m) the
// reversed feet set off an energy blow-up at the floor at dt2 and dt3 for both bases (LME dt2 at
// 0.138 s, MLS dt3 at 0.037 s); with the stop every run completes. For a foot already at rest the two
// agree. The MPM stepper keeps u_t = 0: its grid carries no history (v, a are the particles'
// projections), and there the stop made the 1-s rolling disk worse (acceleration ratio 1.026 at
// h = 0.02 m, dt1; examples/implicit-rolling-disk-incline/README.md).
// After a converged step every point also gets its velocity v_p = sum_I N_I(x_p^n) v_I^{n+1} (for the
// writers and the energies: the nodes carry the history) and its Cauchy stress from the material's
// converged update, which advances the plastic state (implicit_material.hpp). The initial nodal
// velocity and acceleration come from a consistent-mass projection (project_to_nodes).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/meshfree/point_residual.hpp"
#include "matpoint/implicit/newton.hpp"
#include "matpoint/implicit/one_sided_boundary.hpp"
#include "matpoint/implicit/particle_newmark/particle_quadrature.hpp"
#include "matpoint/implicit/sparse_assembly.hpp"
#include "matpoint/particles/remove_particles.hpp"
#include "matpoint/shape/meshfree_stencils.hpp"

namespace matpoint::implicit {

/// The nodes and material points of a meshfree body.
template <int D>
struct MeshfreeBody {
  std::vector<Vec<D>> node_x, node_v, node_a;  // positions x^n, velocities, accelerations
  std::vector<char> fixed;                     // one flag per dof (node * D + i): du = 0
  std::vector<Vec<D>> point_x;
  std::vector<double> point_mass, point_volume0;
  std::vector<Mat<D>> point_F;
  std::vector<int> point_material;  // index into the stepper's materials (empty: all 0)
  std::vector<double> point_state;  // material history, state_stride values per point
  int state_stride = 0;
  // Written by each converged step: v_p = sum_I N_I(x_p^n) v_I, a_p likewise (empty before the first
  // step), the Cauchy stress (and sigma_zz in 2-D).
  std::vector<Vec<D>> point_v, point_a;
  std::vector<Mat<D>> point_stress;
  std::vector<double> point_stress_zz;

  [[nodiscard]] Index dofs() const { return static_cast<Index>(node_x.size()) * D; }
  /// Drops the points that `gone` flags (one flag per point), keeping the others' order.
  void remove_points(const std::vector<char>& gone) {
    for (auto* a : {&point_x, &point_v}) keep_unflagged(*a, gone, 1);
    if (!point_a.empty()) keep_unflagged(point_a, gone, 1);
    for (auto* a : {&point_mass, &point_volume0, &point_stress_zz}) keep_unflagged(*a, gone, 1);
    for (auto* a : {&point_F, &point_stress}) keep_unflagged(*a, gone, 1);
    keep_unflagged(point_material, gone, 1);
    keep_unflagged(point_state, gone, static_cast<std::size_t>(state_stride));
  }
  [[nodiscard]] int material(std::size_t p) const { return point_material.empty() ? 0 : point_material[p]; }
  [[nodiscard]] const double* state(std::size_t p) const {
    return state_stride > 0 ? &point_state[p * static_cast<std::size_t>(state_stride)] : nullptr;
  }
  [[nodiscard]] double* state(std::size_t p) {
    return state_stride > 0 ? &point_state[p * static_cast<std::size_t>(state_stride)] : nullptr;
  }
};

struct MeshfreeStepOptions {
  MeshfreeParameters shape;              // basis, radius, dilation / gamma, repairs
  NewmarkParameters newmark{0.25, 0.5};  // the paper's average acceleration (extraction §4)
  bool quasi_static = false;             // no inertia (the static cantilever)
  bool multipliers = true;               // Dirichlet conditions on the field (see above) or on nodal values
  NewtonOptions newton{};
  LinearSolverOptions linear{};
  /// Each step starts from the nodes' v and a projected from the points' (our repair, see the top
  /// of this file); false: the nodes carry their own history, as the paper's Algorithm 2 does.
  bool project_history = true;
};

/// A node whose consistent-mass diagonal sum_p m_p N_I(x_p)^2 is below this fraction of the largest
/// node's is idle for the step (held at du = 0, at rest): the points hardly see it, and its equation
/// would make the matrix nearly singular (condition number of order 1 / fraction). The fraction is
/// small enough that holding such a node changes the field by its weight, about this much.
inline constexpr double kIdleMassFraction = 1e-8;

template <int D, class Material>
class MeshfreeStepper {
 public:
  MeshfreeStepper(const Material& material, MeshfreeStepOptions options)
      : MeshfreeStepper(std::vector<Material>{material}, std::move(options)) {}
  /// One material per MeshfreeBody::point_material index.
  MeshfreeStepper(std::vector<Material> materials, MeshfreeStepOptions options)
      : materials_(std::move(materials)),
        options_(std::move(options)),
        solver_(make_linear_solver(options_.linear)) {
    options_.newton.components = D;
  }

  /// Advances body by dt under the body force b; returns Newton's result (the body is unchanged
  /// unless it converged). A point without usable shape functions fails the step.
  /// `walls` (optional): the one-sided walls, their candidates found on the body's step-start points
  /// (OneSidedBoundary::start_step), with the penalty stiffness `wall_stiffness`.
  NewtonResult step(MeshfreeBody<D>& body, double dt, const Vec<D>& b, OneSidedBoundary<D>* walls = nullptr,
                    double wall_stiffness = 0.0) {
    NewtonResult result;
    if (!prepare(body, result)) return result;
    if (!project_history(body)) {
      result.status = NewtonStatus::LinearSolveFailed;
      result.message = "the projection of the points' velocities and accelerations to the nodes failed";
      return result;
    }
    const auto point_data = step_data(body, dt, b);
    const auto points = static_cast<Index>(stencils_.size());
    AssembleFunction assemble = [&](const Eigen::VectorXd& u, Eigen::VectorXd& R, SparseMatrix* K) {
      const auto t0 = std::chrono::steady_clock::now();
      assembly_.assemble(
          [&](Index p, std::span<const Index> dofs, double* r, double* k) {
            std::vector<double> local(dofs.size());
            for (std::size_t i = 0; i < dofs.size(); ++i) local[i] = u[dofs[i]];
            if (p < points) {
              const auto q = static_cast<std::size_t>(p);
              meshfree_point_residual<D>(
                  point_data[q], materials_[static_cast<std::size_t>(body.material(q))], local.data(), r, k);
              for (std::size_t f = first_foot_[q]; f < first_foot_[q + 1]; ++f)
                foot_residual(feet_[f], local.data(), r, k);  // the point's feet: the same cloud
              if (k != nullptr && !std::all_of(r, r + dofs.size(), [](double x) { return std::isfinite(x); }))
                note_non_finite_point(p);  // a Newton iterate's (a line-search trial may be non-finite)
            } else {
              constraint_residual(p - points, local.data(), r, k);
            }
          },
          R, K);
      assembly_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return R.allFinite();
    };
    Eigen::VectorXd du;
    if (walls != nullptr) candidate_feet(*walls, body, wall_stiffness, dt);
    for (int solves = 1;; ++solves) {  // one solve, or one per change of the walls' contact set
      if (walls != nullptr) {
        feet_.clear();
        for (std::size_t c = 0; c < candidates_.size(); ++c)
          if (walls->in_contact()[c] != 0) feet_.push_back(candidates_[c]);
        index_feet_by_point();
      }
      // A re-solve after the contact set changed starts from the last round's solution.
      if (solves == 1) du = Eigen::VectorXd::Zero(body.dofs() + multiplier_dofs());
      non_finite_point_ = -1;
      result = newton_solve(assemble, assembly_.pattern_version(), *solver_, du, options_.newton);
      round_off_stops_ += result.round_off_stop ? 1 : 0;
      newton_iterations_ += result.iterations();
      if (walls == nullptr || !result.converged() || solves >= walls->max_rounds()) break;
      std::vector<double> inward(candidates_.size());
      for (std::size_t c = 0; c < candidates_.size(); ++c)
        inward[c] =
            -candidates_[c].outward * foot_displacement(candidates_[c], du, candidates_[c].normal_axis);
      if (!walls->update(inward)) break;
    }
    if (result.status == NewtonStatus::AssemblyFailed && non_finite_point_ >= 0)
      result.message = "non-finite residual of a point " +
                       std::string(result.history.empty() ? "at the step's start" : "at a Newton iterate");
    if (result.converged()) advance(body, du, dt);
    last_increment_ = du.head(body.dofs());
    return result;
  }

  /// The nodal field X (node-major) whose consistent-mass projection matches each point's y_p, with
  /// the internal force of the points' present stress on the right-hand side when `internal_force`:
  ///   sum_p m_p N_I (sum_J N_J X_J - y_p) + [V0_p tau_p grad_n N_I] = 0,
  /// the fixed dofs (or with multipliers the field at the fixed nodes) held at 0. With y_p = b this
  /// is the initial acceleration M a^0 = f_ext - f_int (Newmark's free fall is exact only with it);
  /// with y_p = v_p, the nodes' initial velocity. A linear solve; false when it failed.
  bool project_to_nodes(const MeshfreeBody<D>& body, const std::vector<Vec<D>>& y, bool internal_force,
                        std::vector<Vec<D>>& X) {
    NewtonResult result;
    return prepare(body, result) && project_prepared(body, y, internal_force, X, /*factorize=*/true);
  }

  /// The nodes' v and a as the consistent-mass projections of the points' v_p and a_p at the
  /// present positions (what each step starts with, see the top of this file); false when it failed.
  bool project_point_history(MeshfreeBody<D>& body) {
    NewtonResult result;
    return prepare(body, result) && project_point_fields(body);
  }

  /// Flags in `gone` (one flag per point) the points that have no usable shape functions at the
  /// body's present positions, as step() would find them; returns how many.
  std::size_t flag_points_without_functions(const MeshfreeBody<D>& body, std::vector<char>& gone) {
    build_meshfree_stencils<D>(body.point_x, body.node_x, options_.shape, stencils_);
    gone.assign(stencils_.size(), 0);
    std::size_t count = 0;
    for (std::size_t p = 0; p < gone.size(); ++p) {
      gone[p] = stencils_.status[p] != MeshfreeStatus::Ok && stencils_.status[p] != MeshfreeStatus::Shepard;
      count += gone[p] != 0;
    }
    return count;
  }

  [[nodiscard]] const MeshfreeRepairCounts& repairs() const { return repairs_; }
  void reset_repairs() { repairs_ = {}; }
  [[nodiscard]] const LinearSolver& linear_solver() const { return *solver_; }
  [[nodiscard]] double assembly_seconds() const { return assembly_seconds_; }
  /// Newton solves so far that converged by the round-off stop (newton.hpp).
  [[nodiscard]] int round_off_stops() const { return round_off_stops_; }
  /// Newton iterations so far, every solve of a step counted (a re-solve after the walls' contact
  /// set changed too, as ParticleNewmarkStepper counts them).
  [[nodiscard]] int newton_iterations() const { return newton_iterations_; }
  [[nodiscard]] int colours() const { return assembly_.colour_count(); }
  [[nodiscard]] const MeshfreeStencils<D>& stencils() const { return stencils_; }
  [[nodiscard]] const Eigen::VectorXd& last_increment() const { return last_increment_; }
  /// The smallest point index whose residual was not finite at a Newton iterate of the last step
  /// (line-search trials aside), or -1.
  [[nodiscard]] Index non_finite_point() const { return non_finite_point_; }

 private:
  void note_non_finite_point(Index p) {
#pragma omp critical(matpoint_meshfree_non_finite)
    if (non_finite_point_ < 0 || p < non_finite_point_) non_finite_point_ = p;
  }

  /// The step's clouds, constraints and assembly blocks at the present positions; false (with the
  /// reason in result) when a point or a constraint has no usable shape functions.
  bool prepare(const MeshfreeBody<D>& body, NewtonResult& result) {
    result.status = NewtonStatus::AssemblyFailed;
    for (const auto* positions : {&body.node_x, &body.point_x})
      for (const auto& x : *positions)
        if (!x.allFinite()) {
          result.message = "a meshfree node or point has a non-finite position";
          return false;
        }
    build_meshfree_stencils<D>(body.point_x, body.node_x, options_.shape, stencils_);
    repairs_ += stencils_.repairs;
    result.status = NewtonStatus::AssemblyFailed;
    if (stencils_.repairs.failed > 0) {
      result.message =
          "meshfree shape functions failed at " + std::to_string(stencils_.repairs.failed) + " points";
      return false;
    }
    find_idle_nodes(body);
    feet_.clear();  // the walls' feet are added to their points' blocks in step() only
    index_feet_by_point();
    if (!build_constraints(body)) {
      result.message = "meshfree shape functions failed at a Dirichlet node";
      return false;
    }
    build_blocks(body);
    return true;
  }

  /// project_to_nodes on the clouds of the last prepare(); `factorize` false: the consistent mass
  /// factorised by the previous call on the same clouds is reused.
  bool project_prepared(const MeshfreeBody<D>& body, const std::vector<Vec<D>>& y, bool internal_force,
                        std::vector<Vec<D>>& X, bool factorize) {
    const auto points = static_cast<Index>(stencils_.size());
    Eigen::VectorXd R;
    SparseMatrix& K = mass_matrix_;  // kept: the factorisation reads it again in later solves
    if (factorize) K = assembly_.pattern();
    assembly_.assemble(
        [&](Index p, std::span<const Index> dofs, double* r, double* k) {
          std::vector<double> zero(dofs.size(), 0.0);
          if (p < points)
            mass_residual(body, static_cast<std::size_t>(p), y[static_cast<std::size_t>(p)], internal_force,
                          r, k);
          else
            constraint_residual(p - points, zero.data(), r, k);
        },
        R, factorize ? &K : nullptr);
    Eigen::VectorXd x;
    if (!R.allFinite() || (factorize && !solver_->factorize(K, assembly_.pattern_version())) ||
        !solver_->solve(-R, x) || !x.allFinite())
      return false;
    X.resize(body.node_x.size());
    for (std::size_t I = 0; I < X.size(); ++I) X[I] = x.segment<D>(static_cast<Index>(I) * D);
    return true;
  }

  /// The nodes' v and a as the consistent-mass projections of the points' (see the top of this
  /// file); nothing before the first step (the points have no acceleration yet).
  bool project_history(MeshfreeBody<D>& body) {
    if (!options_.project_history || body.point_a.size() != stencils_.size()) return true;
    return project_point_fields(body);
  }
  /// v_I and a_I from v_p and a_p on the clouds of the last prepare(), one factorisation for both.
  bool project_point_fields(MeshfreeBody<D>& body) {
    return project_prepared(body, body.point_v, false, body.node_v, /*factorize=*/true) &&
           project_prepared(body, body.point_a, false, body.node_a, /*factorize=*/false);
  }

  /// Point p's block of the consistent-mass projection (project_to_nodes) at X = 0: r_Ii = m_p N_I
  /// (-y_i) [+ V0 sum_j tau_ij G_Ij], K_IiJj = m_p N_I N_J delta_ij (K null: the residual only).
  void mass_residual(const MeshfreeBody<D>& body, std::size_t p, const Vec<D>& y, bool internal_force,
                     double* r, double* K) const {
    const auto first = static_cast<std::size_t>(stencils_.offset[p]);
    const std::size_t n = static_cast<std::size_t>(stencils_.offset[p + 1]) - first, m = n * D;
    const double mass = body.point_mass[p];
    Mat<D> tau = Mat<D>::Zero();
    if (internal_force)
      tau = kirchhoff_stress_of<double, D>(materials_[static_cast<std::size_t>(body.material(p))],
                                           body.point_F[p], body.state(p), 0.0);
    for (std::size_t I = 0; I < n; ++I) {
      const double NI = stencils_.N[first + I];
      const Vec<D> f = -mass * NI * y + body.point_volume0[p] * tau * stencils_.dN[first + I];
      for (int i = 0; i < D; ++i) {
        r[I * D + i] = f[i];
        if (K != nullptr)
          for (std::size_t J = 0; J < n; ++J)
            K[(I * D + i) * m + J * D + i] = mass * NI * stencils_.N[first + J];
      }
    }
  }

  /// The fixed nodes as constraint points (multipliers on): their positions' shape functions. An
  /// idle fixed node (the body has left it, e.g. a floor node the toe has run past) holds no field:
  /// its constraint is dropped (its cloud may be a line of floor nodes, a singular moment matrix).
  bool build_constraints(const MeshfreeBody<D>& body) {
    constrained_.clear();
    std::vector<Vec<D>> x;
    if (options_.multipliers)
      for (std::size_t I = 0; I < body.node_x.size(); ++I)
        for (int i = 0; i < D && !idle_[I]; ++i)
          if (body.fixed[I * D + i]) {
            constrained_.push_back(static_cast<Index>(I));
            x.push_back(body.node_x[I]);
            break;
          }
    build_meshfree_stencils<D>(x, body.node_x, options_.shape, constraint_stencils_);
    // A node on the hull boundary is ill conditioned for LME, and still exact; an MLS node whose
    // cloud has become a line (a floor node the body is leaving) has Shepard functions, whose
    // weighted mean is still a valid condition on the field there.
    for (const auto st : constraint_stencils_.status)
      if (st != MeshfreeStatus::Ok && st != MeshfreeStatus::IllConditioned && st != MeshfreeStatus::Shepard)
        return false;
    return true;
  }

  [[nodiscard]] Index multiplier_dofs() const { return static_cast<Index>(constrained_.size()) * D; }

  /// The idle nodes, those the points hardly see (see kIdleMassFraction), from the points' stencils:
  /// in no cloud a node has neither mass nor stiffness and the matrix is singular; at the edge of
  /// the clouds (the smooth MLS weight vanishes there) its row is nearly zero and so is the
  /// factorisation's pivot.
  void find_idle_nodes(const MeshfreeBody<D>& body) {
    std::vector<double> mass(body.node_x.size(), 0.0);  // diagonal of the consistent mass, sum_p m_p N_I^2
    for (std::size_t p = 0; p < stencils_.size(); ++p)
      for (auto k = stencils_.offset[p]; k < stencils_.offset[p + 1]; ++k)
        mass[static_cast<std::size_t>(stencils_.node[k])] +=
            body.point_mass[p] * stencils_.N[k] * stencils_.N[k];
    const double largest = mass.empty() ? 0.0 : *std::max_element(mass.begin(), mass.end());
    idle_.assign(mass.size(), 0);
    for (std::size_t I = 0; I < mass.size(); ++I) {
      idle_[I] = !(mass[I] > kIdleMassFraction * largest);
      repairs_.idle_nodes += idle_[I];
    }
  }

  /// Blocks: the points' clouds, then each constraint's cloud and its D multipliers (those of the
  /// free components are held at zero as Dirichlet dofs). Idle nodes are held at du = 0.
  void build_blocks(const MeshfreeBody<D>& body) {
    offsets_.assign(1, 0);
    block_dofs_.clear();
    auto add_cloud = [&](const MeshfreeStencils<D>& s, std::size_t p) {
      for (auto k = s.offset[p]; k < s.offset[p + 1]; ++k)
        for (int i = 0; i < D; ++i) block_dofs_.push_back(static_cast<Index>(s.node[k]) * D + i);
    };
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      add_cloud(stencils_, p);
      offsets_.push_back(static_cast<Index>(block_dofs_.size()));
    }
    std::vector<char> dirichlet(static_cast<std::size_t>(body.dofs() + multiplier_dofs()), 0);
    if (options_.multipliers) {
      for (std::size_t c = 0; c < constrained_.size(); ++c) {
        add_cloud(constraint_stencils_, c);
        for (int i = 0; i < D; ++i) {
          const Index m = body.dofs() + static_cast<Index>(c) * D + i;
          block_dofs_.push_back(m);
          dirichlet[static_cast<std::size_t>(m)] =
              !body.fixed[static_cast<std::size_t>(constrained_[c] * D + i)];
        }
        offsets_.push_back(static_cast<Index>(block_dofs_.size()));
      }
    } else {
      std::copy(body.fixed.begin(), body.fixed.end(), dirichlet.begin());
    }
    for (std::size_t I = 0; I < idle_.size(); ++I)
      if (idle_[I])
        for (int i = 0; i < D; ++i) dirichlet[I * D + static_cast<std::size_t>(i)] = 1;
    assembly_.build(body.dofs() + multiplier_dofs(), offsets_, block_dofs_, dirichlet);
  }

  /// feet_ sorted by point, and first_foot_: point q's feet are feet_[first_foot_[q] ..
  /// first_foot_[q + 1]). A foot's penalty acts on its point's cloud, so it is assembled with the
  /// point's block: the sparse pattern, its colouring and the solver's symbolic analysis stay those
  /// of the step's clouds while the contact set changes (as separate blocks, every change rebuilt
  /// the pattern: half of a GMM rolling-disk run's time, measured with perf on 2026-11-28).
  void index_feet_by_point() {
    std::stable_sort(feet_.begin(), feet_.end(),
                     [](const MeshfreeFoot& a, const MeshfreeFoot& b) { return a.point < b.point; });
    first_foot_.assign(stencils_.size() + 1, 0);
    for (const MeshfreeFoot& foot : feet_) ++first_foot_[foot.point + 1];
    for (std::size_t q = 0; q < stencils_.size(); ++q) first_foot_[q + 1] += first_foot_[q];
  }

  /// A one-sided wall's candidate foot on point p's cloud: u(x_f) = sum_J W_J du_J.
  struct MeshfreeFoot {
    std::size_t point = 0;
    std::vector<double> W;
    int normal_axis = 0;
    double outward = -1.0, gap = 0.0, stiffness = 0.0;
    bool no_slip = true;
    Vec<D> tangential_rest = Vec<D>::Zero();  // the no-slip springs' rest displacement (see the top)
  };

  /// The walls' candidates as feet on their points' clouds (see the top of this file).
  void candidate_feet(const OneSidedBoundary<D>& walls, const MeshfreeBody<D>& body, double stiffness,
                      double dt) {
    candidates_.clear();
    for (const WallContact<D>& c : walls.candidates()) {
      MeshfreeFoot foot{c.particle, {}, c.plane.axis, c.plane.outward, c.gap, stiffness, c.no_slip};
      const Vec<D> offset = c.foot - body.point_x[c.particle];
      Vec<D> v = Vec<D>::Zero(), a = Vec<D>::Zero();  // the foot's Newmark history, from the nodes'
      for (auto k = stencils_.offset[c.particle]; k < stencils_.offset[c.particle + 1]; ++k) {
        const double W = stencils_.N[k] + stencils_.dN[k].dot(offset);
        const auto node = static_cast<std::size_t>(stencils_.node[k]);
        foot.W.push_back(W);
        v += W * body.node_v[node], a += W * body.node_a[node];
      }
      if (c.no_slip)
        foot.tangential_rest =
            newmark_stop_displacement<D>(v, a, dt, options_.newmark.beta, options_.newmark.gamma);
      candidates_.push_back(std::move(foot));
    }
  }
  /// Component i of a foot's displacement over the step.
  double foot_displacement(const MeshfreeFoot& foot, const Eigen::VectorXd& du, int i) const {
    double s = 0.0;
    std::size_t J = 0;
    for (auto k = stencils_.offset[foot.point]; k < stencils_.offset[foot.point + 1]; ++k, ++J)
      s += foot.W[J] * du[static_cast<Index>(stencils_.node[k]) * D + i];
    return s;
  }
  /// A foot's penalty on its point's cloud (dofs node-major, added to the point's block): add_foot_penalty.
  static void foot_residual(const MeshfreeFoot& foot, const double* u, double* r, double* K) {
    add_foot_penalty<D>(foot.W, foot.normal_axis, foot.outward, foot.gap, foot.no_slip, foot.stiffness, u, r,
                        K, foot.tangential_rest.data());
  }

  /// Constraint c with multipliers l_i (the last D local dofs): r_Ji += l_i N_J, r_li = sum_J N_J du_Ji.
  void constraint_residual(Index c, const double* u, double* r, double* K) const {
    const auto first = static_cast<std::size_t>(constraint_stencils_.offset[static_cast<std::size_t>(c)]);
    const auto n =
        static_cast<std::size_t>(constraint_stencils_.offset[static_cast<std::size_t>(c) + 1]) - first;
    const std::size_t m = n * D + D, l = n * D;
    for (std::size_t J = 0; J < n; ++J) {
      const double N = constraint_stencils_.N[first + J];
      for (int i = 0; i < D; ++i) {
        r[J * D + i] += u[l + i] * N;
        r[l + i] += N * u[J * D + i];
        if (K != nullptr) K[(J * D + i) * m + l + i] = K[(l + i) * m + J * D + i] = N;
      }
    }
  }

  /// Per point: its stencil, and a_p's known part from the nodes' history (consistent mass:
  /// a_p = sum_I N_I a_I with a_I = c du_I + c_v v_I + c_a a_I).
  std::vector<MeshfreePointData<D>> step_data(const MeshfreeBody<D>& body, double dt, const Vec<D>& b) const {
    const NewmarkCoefficients c(options_.newmark, dt);
    std::vector<MeshfreePointData<D>> data(stencils_.size());
    for (std::size_t p = 0; p < data.size(); ++p) {
      const auto first = static_cast<std::size_t>(stencils_.offset[p]),
                 last = static_cast<std::size_t>(stencils_.offset[p + 1]);
      auto& q = data[p];
      q.N = std::span<const double>(stencils_.N.data() + first, last - first);
      q.G = std::span<const Vec<D>>(stencils_.dN.data() + first, last - first);
      q.mass = body.point_mass[p], q.volume0 = body.point_volume0[p], q.F_old = body.point_F[p], q.dt = dt;
      q.state = body.state(p);
      Vec<D> known = Vec<D>::Zero();
      if (!options_.quasi_static) {
        q.inertia_coefficient = c.displacement;
        for (std::size_t k = first; k < last; ++k)
          known += stencils_.N[k] * c.known<D>(body.node_v[static_cast<std::size_t>(stencils_.node[k])],
                                               body.node_a[static_cast<std::size_t>(stencils_.node[k])]);
      }
      q.known_minus_b = known - b;
    }
    return data;
  }

  void advance(MeshfreeBody<D>& body, const Eigen::VectorXd& du, double dt) const {
    const std::size_t points = stencils_.size();
    body.point_v.resize(points, Vec<D>::Zero());
    body.point_stress.resize(points, Mat<D>::Zero());
    body.point_stress_zz.resize(points, 0.0);
    for (std::size_t p = 0; p < points; ++p) {
      Mat<D> H = Mat<D>::Identity();
      for (auto k = stencils_.offset[p]; k < stencils_.offset[p + 1]; ++k) {
        const Vec<D> d = du.segment<D>(static_cast<Index>(stencils_.node[k]) * D);
        body.point_x[p] += stencils_.N[k] * d;
        H += d * stencils_.dN[k].transpose();
      }
      body.point_F[p] = H * body.point_F[p];
      body.point_stress[p] =
          updated_stress_of<D>(materials_[static_cast<std::size_t>(body.material(p))], body.point_F[p],
                               body.state(p), body.point_stress_zz[p], dt);
    }
    const std::vector<Vec<D>> node_motion = field_at_nodes(body, du);
    const NewmarkCoefficients c(options_.newmark, dt);
    for (std::size_t I = 0; I < body.node_x.size(); ++I) {
      const Vec<D> d = du.segment<D>(static_cast<Index>(I) * D);
      body.node_x[I] += node_motion[I];
      if (options_.quasi_static) continue;
      if (idle_[I]) {  // no equation: it stays where the body left it, at rest, until a cloud reaches it
        body.node_v[I].setZero(), body.node_a[I].setZero();
        continue;
      }
      const Vec<D> a = c.displacement * d + c.known<D>(body.node_v[I], body.node_a[I]);
      body.node_v[I] += dt * ((1.0 - options_.newmark.gamma) * body.node_a[I] + options_.newmark.gamma * a);
      body.node_a[I] = a;
    }
    body.point_a.resize(points, Vec<D>::Zero());
    for (std::size_t p = 0; p < points; ++p) {  // the points' velocity from the nodes' new one
      body.point_v[p].setZero();
      body.point_a[p].setZero();
      for (auto k = stencils_.offset[p]; k < stencils_.offset[p + 1]; ++k) {
        body.point_v[p] += stencils_.N[k] * body.node_v[static_cast<std::size_t>(stencils_.node[k])];
        body.point_a[p] += stencils_.N[k] * body.node_a[static_cast<std::size_t>(stencils_.node[k])];
      }
    }
  }

  /// The field's increment sum_J N_J(x_I) du_J at every node's step-start position (see the top of
  /// this file); a node whose functions cannot be computed there moves by its own du_I.
  std::vector<Vec<D>> field_at_nodes(const MeshfreeBody<D>& body, const Eigen::VectorXd& du) const {
    MeshfreeStencils<D> at;
    build_meshfree_stencils<D>(body.node_x, body.node_x, options_.shape, at);
    std::vector<Vec<D>> out(body.node_x.size());
    for (std::size_t I = 0; I < out.size(); ++I) {
      const MeshfreeStatus st = at.status[I];
      if (st != MeshfreeStatus::Ok && st != MeshfreeStatus::Shepard && st != MeshfreeStatus::IllConditioned) {
        out[I] = du.segment<D>(static_cast<Index>(I) * D);
        continue;
      }
      out[I].setZero();
      for (auto k = at.offset[I]; k < at.offset[I + 1]; ++k)
        out[I] += at.N[static_cast<std::size_t>(k)] * du.segment<D>(static_cast<Index>(at.node[k]) * D);
    }
    return out;
  }

  std::vector<Material> materials_;
  MeshfreeStepOptions options_;
  std::unique_ptr<LinearSolver> solver_;
  SparseAssembly assembly_;
  SparseMatrix mass_matrix_;  // of the projections (project_prepared)
  MeshfreeStencils<D> stencils_, constraint_stencils_;
  std::vector<Index> constrained_;  // nodes with a fixed dof (multipliers on)
  std::vector<char> idle_;          // per node: in no point's cloud this step
  MeshfreeRepairCounts repairs_;
  std::vector<Index> offsets_, block_dofs_;
  std::vector<MeshfreeFoot> candidates_, feet_;  // the walls' candidate feet; those in contact
  std::vector<std::size_t> first_foot_{0};       // feet_ by point (index_feet_by_point)
  Eigen::VectorXd last_increment_;
  double assembly_seconds_ = 0.0;
  int round_off_stops_ = 0;
  int newton_iterations_ = 0;
  Index non_finite_point_ = -1;
};

}  // namespace matpoint::implicit
