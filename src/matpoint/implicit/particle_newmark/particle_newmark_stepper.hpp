// One time step of an implicit MPM with particles as quadrature points, on a fixed background
// mesh (u_reset = 0, so x~ = the mesh's nodes). Two formulations share it; they differ only in
// where Newmark's known terms live:
//   - Aulisa & Capodaglio's particle Newmark (extraction §9): a_p = u~_p / (beta dt^2) - v_p^n /
//     (beta dt) - (1 - 2 beta) / (2 beta) a_p^n at each particle (eq. (21)); after the step the
//     particle's own a_p, v_p follow eqs. (19), (17);
//   - Iaconeta 2017's updated-Lagrangian MPM (§4.1, Algorithm 1): the particles' momentum and
//     m a are projected to the nodes (eqs. (38)-(41); nodal_projection.hpp), Newmark's predictor acts on the
//     nodal v~_I, a~_I (eqs. (43), (44)), so the particle sees a_p = sum_I N_I a_I; after the step a_p^{n+1}
//     = sum_I N_I a_I^{n+1} (47) and v_p^{n+1} = v_p^n + dt ((1 - gamma) a_p^n + gamma a_p^{n+1}) (48, the
//     trapezoidal rule for gamma = 1/2);
//   - either with `static_analysis`: no inertia, equilibrium under the step's load (Iaconeta §4.1.1,
//     the static cantilever of §5.1).
// The steps:
//   0. locate the particles (host element, xi) in x~; the receding switches from v_p^n (A4);
//   1. active set, flags M_E and C_E (§5.2), particles sorted by element as quadrature points;
//   2. Newton on u~ from u~ = 0 (§6), K by AD, the generic assembly and linear solver;
//   3. commit at the particles (§7, eqs. (35), (19), (17), (34)): u_p, a_p, v_p, F_p, x_p;
//   4. the grid is reset to 0 (nothing to keep: u~ lives only inside the step).
// Particle data: matpoint's ParticleSet<D> (x, v, mass, volume0, F, stress, material) plus the
// implicit extras (acceleration, host element, xi).
// FE bodies (fem/fe_body.hpp, Aulisa & Capodaglio §4) join the same system: their elements are
// always active, their Gauss points are quadrature points of fixed host and xi, their nodes keep
// u, v, a (nodal Newmark, eq. (46)), and x~ of their nodes is the deformed position at the step
// start (the reference configuration of eqs. (2), (8a)); no particle is located in them.
#pragma once

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/fem/fe_body.hpp"
#include "matpoint/fem/reset_extension.hpp"
#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/newton.hpp"
#include "matpoint/implicit/one_sided_boundary.hpp"
#include "matpoint/implicit/particle_newmark/element_flags.hpp"
#include "matpoint/implicit/particle_newmark/nodal_projection.hpp"
#include "matpoint/implicit/particle_newmark/particle_newmark_system.hpp"
#include "matpoint/mesh/point_locator.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint::implicit {

/// What the implicit particle update keeps beyond ParticleSet<D>.
template <int D>
struct ImplicitParticleState {
  std::vector<Vec<D>> acceleration;  // a_p^n
  std::vector<Index> element;        // host element in x~ (-1: not located yet)
  std::vector<Vec<D>> xi;            // local coordinates in the host element
  void resize(std::size_t n) {
    acceleration.resize(n, Vec<D>::Zero());
    element.resize(n, -1);
    xi.resize(n, Vec<D>::Zero());
  }
};

template <int D>
struct ParticleNewmarkOptions {
  NewmarkParameters newmark;
  Vec<D> gravity = Vec<D>::Zero();
  /// A17: initial particle acceleration a^0 = 0 (the paper) or a^0 = b (consistent with gravity).
  bool initial_acceleration_from_body_force = false;
  FlagRule flag_rule = FlagRule::Paper;
  SoftStiffnessTable soft_stiffness;   // C_E(M_E); empty: no soft stiffness
  std::vector<char> not_fully_active;  // per node, for FlagRule::Code (A13)
  bool receding_in_gradient = true;    // A24
  bool newmark_at_grid = false;        // Iaconeta 2017's nodal Newmark (see the top of this file)
  bool static_analysis = false;        // no inertia
  bool small_strain = false;           // geometrically linear, Hooke (particle_residual.hpp)
  NewtonOptions newton;
  LinearSolverOptions linear;
  std::vector<OneSidedNode> one_sided;  // nodes of one-sided boundaries (one_sided_boundary.hpp)
  /// (body index, reference point) -> inside the body's shape: where the one-sided walls find the
  /// bodies' surfaces (empty: the particles' domains stand for them)
  std::function<bool(int, const Vec<D>&)> body_contains;
  int max_one_sided_rounds = kMaxOneSidedRounds;  // Newton solves per step while the held set changes
};

struct StepReport {
  NewtonResult newton;
  Index active_elements = 0;
  Index lost_particles = 0;       // particles outside the mesh (the step is refused, A22)
  double assembly_seconds = 0.0;  // residual + Jacobian assembly (the linear solver keeps its own times)
  double boundary_work = 0.0;     // work of the moving Dirichlet conditions on the body (trapezoidal)
  double load_work = 0.0;         // work of the surface loads (trapezoidal)
  int solves = 0;                 // Newton solves (one-sided boundaries: one per change of the held set)
  int iterations = 0;             // Newton iterations of all of them
  int round_off_stops = 0;        // solves that converged by Newton's round-off stop
  /// Particle Newmark only: the work of the step-start equilibrium defect e = M a^n + f_int^n - f_ext^n
  /// over the step, (1/2) u~ . e = (1/2) sum_p [m_p (a_p^n - b^n) . u~_p + V0_p tau_p^n : grad~ u~*_p]
  /// (docs/theory/implicit.md, "The energy audit": K + U changes by this, up to O(dt^3) and a
  /// bounded (beta - 1/4) term).
  double defect_work = 0.0;
  [[nodiscard]] bool ok() const { return lost_particles == 0 && newton.converged(); }
};

template <class E, class Material>
class ParticleNewmarkStepper {
 public:
  static constexpr int D = E::kDim;

  /// dirichlet: one flag per dof (node * D + component), value 0 (walls at rest). receding: C_c of
  /// (element, local face) pairs on Dirichlet faces (§5; empty: no correction).
  ParticleNewmarkStepper(const mesh::Mesh<D>& mesh, std::vector<Material> materials,
                         ParticleNewmarkOptions<D> options, std::vector<char> dirichlet,
                         std::map<std::pair<Index, int>, double> receding = {},
                         fem::FeBodies<E> fe_bodies = {})
      : mesh_(mesh),
        materials_(std::move(materials)),
        options_(std::move(options)),
        dirichlet_(std::move(dirichlet)),
        receding_(std::move(receding)),
        reference_(mesh.nodes),
        locator_(mesh, mesh.nodes),
        solver_(make_linear_solver(options_.linear)),
        one_sided_(options_.one_sided, options_.max_one_sided_rounds, options_.body_contains),
        fe_(std::move(fe_bodies)) {
    options_.newton.components = D;
    // A one-sided wall's nodes are free: the wall acts on the particles' feet (one_sided_boundary.hpp).
    for (const OneSidedNode& n : options_.one_sided)
      for (int a = 0; a < D; ++a)
        if (n.all_components || a == n.plane.axis) dirichlet_[static_cast<std::size_t>(n.node * D + a)] = 0;
    if (fe_.empty()) return;
    if (options_.initial_acceleration_from_body_force) fe_.start_from_body_force(mesh_, options_.gravity);
    locator_.exclude(fe_.element_mask());
    std::vector<char> background(fe_.element_mask().size());
    for (std::size_t e = 0; e < background.size(); ++e) background[e] = fe_.element_mask()[e] == 0 ? 1 : 0;
    extension_.emplace(mesh_, fe_.node_mask(), dirichlet_, background);
  }

  /// Sizes the implicit extras and sets a^0 (A17).
  void initialize(const ParticleSet<D>& particles, ImplicitParticleState<D>& state) const {
    state.resize(particles.size());
    for (auto& a : state.acceleration)
      a = options_.initial_acceleration_from_body_force ? options_.gravity : Vec<D>::Zero();
  }

  /// Advances the particles by dt. On a failed step (report.ok() false) the particles are unchanged.
  StepReport step(ParticleSet<D>& particles, ImplicitParticleState<D>& state, double dt);

  [[nodiscard]] const LinearSolver& linear_solver() const { return *solver_; }
  /// The FE bodies' state (Gauss points, nodes); empty without FE bodies.
  [[nodiscard]] const fem::FeBodies<E>& fe_bodies() const { return fe_; }
  fem::FeBodies<E>& fe_bodies() { return fe_; }
  /// x~: the mesh's nodes, but those of FE bodies at their deformed position of the step start.
  [[nodiscard]] const std::vector<Vec<D>>& reference_nodes() const { return reference_; }
  /// After a restart: x~ from the FE bodies' nodal displacements.
  void restore_reference_nodes() {
    if (fe_.empty()) return;
    for (std::size_t n = 0; n < reference_.size(); ++n) reference_[n] = mesh_.nodes[n] + fe_.displacement[n];
    extension_->apply(fe_.displacement, reference_);
    locator_.update(reference_);
    ++reference_version_;
  }
  /// The nodal u~ of the last completed step (node-major, D per node; empty before the first).
  [[nodiscard]] const Eigen::VectorXd& last_increment() const { return last_increment_; }
  /// The body force per unit mass of the next steps (loads.gravity_scale changes it in time).
  void set_gravity(const Vec<D>& gravity) { options_.gravity = gravity; }
  /// After a restart: the body force of the last completed step, which a^n balances (defect work).
  void set_gravity_at_start(const Vec<D>& gravity) { gravity_at_start_ = gravity; }
  /// u~ of Dirichlet dofs that move in the next step (dof, displacement over the step); the other
  /// Dirichlet dofs stay at 0.
  void set_prescribed(std::vector<std::pair<Index, double>> prescribed) {
    prescribed_ = std::move(prescribed);
  }
  /// The surface loads of the next step at its end (the equilibrium Newton solves) and at its start
  /// (for the trapezoidal work; the grid is reset, so both act on the faces as meshed plus u~).
  void set_face_loads(std::vector<FaceLoad<D>> at_end, std::vector<FaceLoad<D>> at_start) {
    loads_end_ = std::move(at_end);
    loads_start_ = std::move(at_start);
  }
  /// The last converged reaction of each moving dof (for the boundary work; a checkpoint keeps it).
  [[nodiscard]] const std::map<Index, double>& reactions() const { return reaction_; }
  void set_reactions(std::map<Index, double> reactions) { reaction_ = std::move(reactions); }

 private:
  bool locate(const ParticleSet<D>& particles, ImplicitParticleState<D>& state, StepReport& report) const;
  void build_quadrature(const ParticleSet<D>& particles, const ImplicitParticleState<D>& state,
                        const NewmarkCoefficients& c);
  /// Returns the step's equilibrium-defect work (StepReport::defect_work).
  double commit(ParticleSet<D>& particles, ImplicitParticleState<D>& state, const Eigen::VectorXd& u,
                double dt);
  /// The velocity at t^n behind each face of background element e: an FE body's, taken at the
  /// face's mid-side node on quadratic faces (Q9, T6: the authors' code, A4) and as the mean of the
  /// two corners on linear ones (Q4, T3), where every node of the face is an FE node; else 0.
  FaceVelocities<E> interface_velocities(Index e) const {
    FaceVelocities<E> out = walls_at_rest<E>();
    if constexpr (D == 2) {
      const auto nodes = mesh_.element_nodes(e);
      const auto node = [&](int local) {
        return static_cast<std::size_t>(nodes[static_cast<std::size_t>(local)]);
      };
      for (int f = 0; f < E::kFaces; ++f) {
        const auto face = E::faces()[static_cast<std::size_t>(f)];
        bool on_fe_body = true;
        for (int local : face) on_fe_body = on_fe_body && fe_.node_mask()[node(local)] != 0;
        if (!on_fe_body) continue;
        static_assert(E::kNodesPerFace == 2 || E::kNodesPerFace == 3,
                      "2-D faces: two corners (+ a mid-side node)");
        if constexpr (E::kNodesPerFace == 3)
          out[static_cast<std::size_t>(f)] = fe_.velocity[node(face[2])];
        else
          out[static_cast<std::size_t>(f)] =
              0.5 * (fe_.velocity[node(face[0])] + fe_.velocity[node(face[1])]);
      }
    }
    return out;
  }
  /// The one-sided walls' candidate feet on their particles' host elements: the foot
  /// moves with its particle, x_f = x_p + F_p r_p, so over the step u~(x_f) = u~(x_p) + grad~ u~(x_p)
  /// d with d = x_f - x_p: weights W_J = N_J(x_p) + grad~ N_J(x_p) . d (exact for the particle's
  /// affine motion; the foot itself may lie in an element without material, where the field is
  /// only extrapolated). The penalty stiffness is k = kFootPenalty (lambda + 2 mu)_max L^(D-2), L
  /// the host element's extent.
  void locate_feet(const ParticleSet<D>& particles, const ImplicitParticleState<D>& state) {
    double modulus = 0.0;
    for (const Material& m : materials_) modulus = std::max(modulus, m.lambda + 2.0 * m.mu);
    feet_.clear();
    for (const WallContact<D>& c : one_sided_.candidates()) {
      const Index element = state.element[c.particle];
      const Vec<D>& xi = state.xi[c.particle];
      const NodeMatrix<E> nodes = gather_nodes<E>(reference_, mesh_.element_nodes(element));
      const double extent = (nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).maxCoeff();
      const Vec<D> offset = c.foot - particles.x[c.particle];
      FootBlock<E> foot{element,
                        E::values(xi, mesh_.element_variant(element)) +
                            physical_gradients<E>(nodes, xi, mesh_.element_variant(element)) * offset,
                        c.plane.axis,
                        c.plane.outward,
                        c.gap,
                        c.no_slip,
                        kFootPenalty * modulus * std::pow(extent, D - 2)};
      feet_.push_back(foot);
    }
  }
  /// The feet in contact this round (added to their host elements' blocks by the system).
  std::vector<FootBlock<E>> feet_in_contact() const {
    std::vector<FootBlock<E>> out;
    for (std::size_t c = 0; c < feet_.size(); ++c)
      if (one_sided_.in_contact()[c] != 0) out.push_back(feet_[c]);
    return out;
  }
  /// u~(x_f) . (-n) of every candidate foot.
  std::vector<double> feet_inward_displacements(const Eigen::VectorXd& u) const {
    std::vector<double> out(feet_.size(), 0.0);
    for (std::size_t c = 0; c < feet_.size(); ++c) {
      const FootBlock<E>& foot = feet_[c];
      const auto nodes = mesh_.element_nodes(foot.element);
      double s = 0.0;
      for (int J = 0; J < E::kNodes; ++J)
        s += foot.W[J] * u[nodes[static_cast<std::size_t>(J)] * D + foot.normal_axis];
      out[c] = -foot.outward * s;
    }
    return out;
  }
  /// F and stress of the FE Gauss point at quadrature entry qo (its element: the block holding qo).
  void commit_gauss_point(std::size_t qo, const Eigen::VectorXd& u, double dt);

  /// The work of the moving conditions over the converged step, sum_d (f_d^n + f_d^{n+1}) / 2 u~_d with
  /// f_d the reaction (the unconstrained residual of dof d; 0 before the first step, a body at rest
  /// and unloaded there); remembers f^{n+1}.
  double boundary_work(const Eigen::VectorXd& u) {
    if (prescribed_.empty()) return 0.0;
    Eigen::VectorXd reaction;
    system_.assemble(u, reaction, nullptr, false);
    double work = 0.0;
    for (const auto& [dof, value] : prescribed_) {
      double& previous = reaction_[dof];
      work += 0.5 * (previous + reaction[dof]) * value;
      previous = reaction[dof];
    }
    return work;
  }

  /// Particle p's material history, null when no material has one (const for the residual's read,
  /// mutable for the commit's update).
  template <class Particles>
  static auto material_history(Particles& particles, std::size_t p) -> decltype(particles.state.data()) {
    return particles.state_stride > 0 ? &particles.state[p * static_cast<std::size_t>(particles.state_stride)]
                                      : nullptr;
  }

  /// Iaconeta eqs. (38)-(41): the nodal v~_I, a~_I (nodal_projection.hpp).
  void project_to_nodes(const ParticleSet<D>& particles, const ImplicitParticleState<D>& state);
  /// The known part of particle p's acceleration (a_p = u~_p / (beta dt^2) + known): eq. (21) at the
  /// particle, or Newmark's nodal predictor interpolated to it, or 0 in a static analysis.
  [[nodiscard]] Vec<D> known_acceleration(const ParticleSet<D>& particles,
                                          const ImplicitParticleState<D>& state, std::size_t p,
                                          const NewmarkCoefficients& c) const;

  const mesh::Mesh<D>& mesh_;
  std::vector<Material> materials_;
  ParticleNewmarkOptions<D> options_;
  std::vector<char> dirichlet_;
  std::map<std::pair<Index, int>, double> receding_;
  std::vector<Vec<D>> reference_;        // x~ (eq. (2)): where the particles are located and gradients taken
  std::uint64_t reference_version_ = 0;  // raised whenever reference_ moves (FE bodies)
  mesh::PointLocator<D> locator_;
  std::unique_ptr<LinearSolver> solver_;
  ActiveSet set_;
  ParticleQuadrature<E> q_;
  std::vector<FaceCoefficients<E>> element_receding_;
  ParticleNewmarkSystem<E, Material> system_;
  std::vector<Vec<D>> node_velocity_, node_acceleration_;  // v~_I, a~_I (grid Newmark only)
  Eigen::VectorXd last_increment_;
  std::vector<std::pair<Index, double>> prescribed_;
  std::map<Index, double> reaction_;  // the last converged reaction of each moving dof
  std::vector<FaceLoad<D>> loads_end_, loads_start_;
  Vec<D> gravity_at_start_ = options_.gravity;  // b^n: the body force of the previous step (defect work)
  OneSidedBoundary<D> one_sided_;
  std::vector<FootBlock<E>> feet_;  // per one-sided candidate: its foot's penalty data
  fem::FeBodies<E> fe_;
  std::optional<fem::ResetExtension<E>> extension_;  // with FE bodies: the background's x~ (8b)
};

template <class E, class Material>
void ParticleNewmarkStepper<E, Material>::project_to_nodes(const ParticleSet<D>& particles,
                                                           const ImplicitParticleState<D>& state) {
  lumped_projection<E>(mesh_, {state.element, state.xi, particles.mass, particles.v, state.acceleration},
                       node_velocity_, node_acceleration_);
}

template <class E, class Material>
auto ParticleNewmarkStepper<E, Material>::known_acceleration(const ParticleSet<D>& particles,
                                                             const ImplicitParticleState<D>& state,
                                                             std::size_t p,
                                                             const NewmarkCoefficients& c) const -> Vec<D> {
  if (options_.static_analysis) return Vec<D>::Zero();
  if (!options_.newmark_at_grid) return c.known<D>(particles.v[p], state.acceleration[p]);
  const auto N = E::values(state.xi[p], mesh_.element_variant(state.element[p]));
  const auto element = mesh_.element_nodes(state.element[p]);
  Vec<D> v = Vec<D>::Zero(), a = Vec<D>::Zero();  // sum_I N_I v~_I, sum_I N_I a~_I
  for (int I = 0; I < E::kNodes; ++I) {
    const auto n = static_cast<std::size_t>(element[static_cast<std::size_t>(I)]);
    v += N[I] * node_velocity_[n], a += N[I] * node_acceleration_[n];
  }
  return c.known<D>(v, a);  // the nodal predictor (44) is linear in v~, a~: interpolate, then apply
}

template <class E, class Material>
bool ParticleNewmarkStepper<E, Material>::locate(const ParticleSet<D>& particles,
                                                 ImplicitParticleState<D>& state, StepReport& report) const {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  Index lost = 0;
#pragma omp parallel for reduction(+ : lost) if (n > kParallelMinimum)
  for (std::ptrdiff_t p = 0; p < n; ++p) {
    const auto loc =
        locator_.locate(particles.x[static_cast<std::size_t>(p)], state.element[static_cast<std::size_t>(p)]);
    if (!loc) {
      ++lost;
      continue;
    }
    state.element[static_cast<std::size_t>(p)] = loc->element;
    state.xi[static_cast<std::size_t>(p)] = loc->xi;
  }
  report.lost_particles = lost;
  return lost == 0;
}

template <class E, class Material>
void ParticleNewmarkStepper<E, Material>::build_quadrature(const ParticleSet<D>& particles,
                                                           const ImplicitParticleState<D>& state,
                                                           const NewmarkCoefficients& c) {
  const ParticlesByElement sorted = sort_particles_by_element(set_, state.element);
  q_.clear();
  element_receding_.assign(set_.active_elements.size(), FaceCoefficients<E>{});
  for (std::size_t k = 0; k < set_.active_elements.size(); ++k) {
    const Index e = set_.active_elements[k];
    // x~; the undeformed mesh under small strain (geometrically linear: FE bodies too)
    const NodeMatrix<E> x =
        gather_nodes<E>(options_.small_strain ? mesh_.nodes : reference_, mesh_.element_nodes(e));
    if (!fe_.empty() && fe_.fe_element(e) >= 0) {  // an FE element: its Gauss points
      fe_.add_quadrature(fe_.fe_element(e), x, mesh_.element_nodes(e), mesh_.element_variant(e), c,
                         options_.static_analysis, options_.gravity, q_);
      q_.close_block();
      continue;
    }
    bool any_face = false;
    for (int f = 0; f < E::kFaces; ++f)
      if (const auto it = receding_.find({e, f}); it != receding_.end()) {
        element_receding_[k][static_cast<std::size_t>(f)] = it->second;
        any_face = true;
      }
    FaceVelocities<E> walls = walls_at_rest<E>();
    if constexpr (RecedingStencil<E>::kSupported)
      if (any_face && !fe_.empty()) walls = interface_velocities(e);
    for (Index o = sorted.begin[k]; o < sorted.begin[k + 1]; ++o) {
      const auto p = static_cast<std::size_t>(sorted.order[static_cast<std::size_t>(o)]);
      std::uint32_t bits = 0;
      if constexpr (RecedingStencil<E>::kSupported)
        if (any_face) bits = receding_switches<E>(x, element_receding_[k], particles.v[p], walls);
      q_.add(static_cast<Index>(p), state.xi[p], x, mesh_.element_variant(e), particles.mass[p],
             particles.volume0[p], particles.material[p], particles.F[p],
             known_acceleration(particles, state, p, c) - options_.gravity, bits,
             material_history(particles, p));
    }
    q_.close_block();
  }
}

template <class E, class Material>
StepReport ParticleNewmarkStepper<E, Material>::step(ParticleSet<D>& particles,
                                                     ImplicitParticleState<D>& state, double dt) {
  StepReport report;
  if (state.element.size() != particles.size()) initialize(particles, state);
  if (!locate(particles, state, report)) {
    report.newton.status = NewtonStatus::AssemblyFailed;
    report.newton.message = std::to_string(report.lost_particles) + " particles outside the mesh";
    return report;
  }
  // Active set, flags, quadrature, system (fixed for the Newton iterations).
  set_ = build_active_set(mesh_.node_count(), mesh_.nodes_per_element, mesh_.connectivity, state.element,
                          fe_.empty() ? std::span<const char>{} : std::span<const char>(fe_.element_mask()));
  report.active_elements = static_cast<Index>(set_.active_elements.size());
  const NewmarkCoefficients c(options_.newmark, dt);
  if (options_.newmark_at_grid && !options_.static_analysis) project_to_nodes(particles, state);
  build_quadrature(particles, state, c);
  typename ParticleNewmarkSystem<E, Material>::StepData data;
  data.mesh = &mesh_;
  data.reference_nodes =
      options_.small_strain ? std::span<const Vec<D>>(mesh_.nodes) : std::span<const Vec<D>>(reference_);
  data.reference_version = options_.small_strain ? 0 : reference_version_;
  data.set = &set_;
  data.quadrature = &q_;
  data.materials = materials_;
  const auto flags =
      element_flags(set_, E::kNodes, mesh_.connectivity, options_.flag_rule, options_.not_fully_active);
  const auto ce = soft_stiffness_factors(flags, options_.soft_stiffness, options_.flag_rule);
  data.soft_stiffness.resize(ce.size());
  for (std::size_t k = 0; k < ce.size(); ++k) {
    double mu = 0.0;  // the shear modulus of the element's MPM body: the largest among its particles
    if (!fe_.empty() && fe_.fe_element(set_.active_elements[k]) >= 0) {  // no soft stiffness in FE bodies
      data.soft_stiffness[k] = 0.0;
      continue;
    }
    for (Index p = q_.begin[k]; p < q_.begin[k + 1]; ++p)
      mu = std::max(mu, materials_[static_cast<std::size_t>(q_.material[static_cast<std::size_t>(p)])].mu);
    data.soft_stiffness[k] = mu * ce[k];
  }
  if (!receding_.empty()) data.receding = element_receding_;
  data.options.inertia_coefficient = options_.static_analysis ? 0.0 : c.displacement;
  data.options.receding_in_gradient = options_.receding_in_gradient;
  data.options.small_strain = options_.small_strain;
  data.options.dt = dt;
  data.face_loads = loads_end_;
  data.face_loads_at_start = loads_start_;

  const auto timed_assembly = [&](const Eigen::VectorXd& x, Eigen::VectorXd& R, SparseMatrix* K) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = system_.assemble(x, R, K);
    report.assembly_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return ok;
  };
  if (!one_sided_.empty()) {
    one_sided_.start_step(particles, dt);
    locate_feet(particles, state);
  }
  Eigen::VectorXd u;
  for (;;) {  // one solve, or one per change of the one-sided walls' contact set
    if (report.solves == 0) {
      data.dirichlet = dirichlet_;
      if (!one_sided_.empty()) data.feet = feet_in_contact();
      system_.setup(std::move(data));
    } else {  // only the feet changed: the blocks, their geometry and the pattern stay
      system_.set_feet(feet_in_contact());
    }
    // u~ = 0 (§6) but at moving Dirichlet dofs, which keep their value (identity rows, zero residual).
    // A re-solve after the contact set changed starts from the last round's solution instead, which
    // differs from the new one only near the feet that changed.
    if (report.solves == 0) u = Eigen::VectorXd::Zero(system_.dof_count());
    for (const auto& [dof, value] : prescribed_) u[dof] = value;
    report.newton =
        newton_solve(timed_assembly, system_.assembly().pattern_version(), *solver_, u, options_.newton);
    ++report.solves;
    report.iterations += report.newton.iterations();
    report.round_off_stops += report.newton.round_off_stop ? 1 : 0;
    if (one_sided_.empty() || !report.newton.converged() || report.solves >= one_sided_.max_rounds()) break;
    if (!one_sided_.update(feet_inward_displacements(u))) break;
  }
  if (report.newton.converged()) {
    report.boundary_work = boundary_work(u);
    report.load_work = system_.surface_load_work(u);
    report.defect_work = commit(particles, state, u, dt);
    gravity_at_start_ = options_.gravity;  // the body force a^{n+1} balances
    if (!fe_.empty()) {
      fe_.commit_nodes(u, options_.newmark, dt, options_.static_analysis, mesh_.nodes, reference_);
      extension_->apply(fe_.displacement, reference_);  // the background's new x~ (8b)
      locator_.update(reference_);
      ++reference_version_;
    }
    last_increment_ = std::move(u);
  }
  return report;
}

template <class E, class Material>
void ParticleNewmarkStepper<E, Material>::commit_gauss_point(std::size_t qo, const Eigen::VectorXd& u,
                                                             double dt) {
  const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(q_.begin.begin(), q_.begin.end(), static_cast<Index>(qo)) - q_.begin.begin() - 1);
  const auto nodes = mesh_.element_nodes(set_.active_elements[k]);
  Mat<D> H = Mat<D>::Identity();  // I + grad~ u~ (25)
  for (int I = 0; I < E::kNodes; ++I)
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) H(i, j) += u[nodes[static_cast<std::size_t>(I)] * D + i] * q_.G[qo](I, j);
  const Index g = fem::FeBodies<E>::gauss_point_of(q_.particle[qo]);
  fe_.commit_gauss_point(g, H, materials_[static_cast<std::size_t>(q_.material[qo])], dt,
                         options_.small_strain);
}

template <class E, class Material>
double ParticleNewmarkStepper<E, Material>::commit(ParticleSet<D>& particles, ImplicitParticleState<D>& state,
                                                   const Eigen::VectorXd& u, double dt) {
  const NewmarkCoefficients c(options_.newmark, dt);
  const double gamma = options_.newmark.gamma;
  const auto count = static_cast<std::ptrdiff_t>(q_.particle.size());
  // The equilibrium defect's work (StepReport::defect_work): Aulisa & Capodaglio's particle Newmark
  // (eqs. (17)-(21)) carries a_p^n from the previous step's grid; on this step's grid
  // M a^n + f_int^n - f_ext^n need not vanish, and Newmark's energy identity gains (1/2) u~ . e.
  const bool audit = !options_.static_analysis && !options_.newmark_at_grid;
  double defect = 0.0;
#pragma omp parallel for reduction(+ : defect) if (count > kParallelMinimum)
  for (std::ptrdiff_t o = 0; o < count; ++o) {
    const auto qo = static_cast<std::size_t>(o);
    if (q_.particle[qo] < 0) {  // a Gauss point of an FE body
      commit_gauss_point(qo, u, dt);
      continue;
    }
    const auto p = static_cast<std::size_t>(q_.particle[qo]);
    const auto nodes = mesh_.element_nodes(state.element[p]);
    std::array<double, E::kNodes * D> ue;
    for (int I = 0; I < E::kNodes; ++I)
      for (int i = 0; i < D; ++i)
        ue[static_cast<std::size_t>(I * D + i)] = u[nodes[static_cast<std::size_t>(I)] * D + i];
    // u_p (35) with the uncorrected u~; F_p (34) with the corrected one where switched.
    Vec<D> up = Vec<D>::Zero();
    for (int I = 0; I < E::kNodes; ++I)
      for (int i = 0; i < D; ++i) up[i] += q_.N[qo][I] * ue[static_cast<std::size_t>(I * D + i)];
    if constexpr (RecedingStencil<E>::kSupported)
      if (q_.receding[qo] != 0) {
        const std::size_t k = static_cast<std::size_t>(
            std::upper_bound(q_.begin.begin(), q_.begin.end(), static_cast<Index>(o)) - q_.begin.begin() - 1);
        apply_receding_correction<E>(q_.receding[qo], element_receding_[k], ue.data());
      }
    Mat<D> H = Mat<D>::Identity();
    for (int I = 0; I < E::kNodes; ++I)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) H(i, j) += ue[static_cast<std::size_t>(I * D + i)] * q_.G[qo](I, j);
    if (audit) {  // tau^n = J^n sigma^n (sigma^n: Hooke's under small strain, on reference gradients)
      const double J = options_.small_strain ? 1.0 : particles.F[p].determinant();
      const Mat<D> grad = H - Mat<D>::Identity();
      defect += 0.5 * (particles.mass[p] * (state.acceleration[p] - gravity_at_start_).dot(up) +
                       particles.volume0[p] * J * (particles.stress[p].cwiseProduct(grad)).sum());
    }
    if (!options_.static_analysis) {
      // (19) at the particle, or Iaconeta (47): sum_I N_I a_I^{n+1}, the same expression with the
      // interpolated nodal predictor; then (17) / Iaconeta (48).
      const Vec<D> a_old = state.acceleration[p];
      const Vec<D> a_new = c.displacement * up + known_acceleration(particles, state, p, c);
      particles.v[p] += dt * ((1.0 - gamma) * a_old + gamma * a_new);
      state.acceleration[p] = a_new;
    }
    particles.F[p] =
        options_.small_strain ? Mat<D>(particles.F[p] + H - Mat<D>::Identity()) : Mat<D>(H * particles.F[p]);
    particles.x[p] += up;
    const Material& m = materials_[static_cast<std::size_t>(particles.material[p])];
    if (options_.small_strain) {  // Hooke on sym(F - 1), as the residual (sigma_zz = lambda tr eps)
      const Mat<D> eps = 0.5 * (particles.F[p] + particles.F[p].transpose()) - Mat<D>::Identity();
      particles.stress[p] = m.lambda * eps.trace() * Mat<D>::Identity() + 2.0 * m.mu * eps;
      if constexpr (D == 2) particles.stress_zz[p] = m.lambda * eps.trace();
      continue;
    }
    double sigma_zz = 0.0;
    particles.stress[p] =
        updated_stress_of<D>(m, particles.F[p], material_history(particles, p), sigma_zz, dt);
    if constexpr (D == 2) particles.stress_zz[p] = sigma_zz;
  }
  return defect;
}

}  // namespace matpoint::implicit
