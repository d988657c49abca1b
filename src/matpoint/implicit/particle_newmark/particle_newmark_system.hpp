// The nonlinear system of one step of Aulisa & Capodaglio's particle-Newmark implicit MPM (§3.3,
// eqs. (26)-(28), (32)): unknowns u~ at every mesh node (node-major: dof = node * D + component),
// blocks
//   - one per active element: the particles' residual (20)-(25) plus the soft stiffness (26) when
//     C_E > 0, Jacobian by forward-mode AD (ad_jacobian.hpp), plus the penalty of each particle foot
//     of the element in contact with a one-sided wall (one_sided_boundary.hpp): (k/2) (g + u~(x_f) .
//     (-n))^2, and (k/2) |P_t u~(x_f)|^2 on a no-slip wall, u~(x_f) = sum_J W_J u~_J on the
//     particle's host element; linear. A foot acts on exactly its host element's dofs, so it joins
//     that block: the sparse pattern, and the solver's symbolic analysis, stay those of the active
//     set while the contact set changes (as blocks of their own, every change rebuilt them);
//   - one per loaded boundary face of an active element: the surface load (surface_load.hpp), its
//     load stiffness by AD for a follower pressure;
//   - one per dof of the nodes in I_ib: the lumped-mass equation (27) summed over the node's inactive
//     elements (linear and diagonal, so the Jacobian is the node mass itself);
// assembled by the generic SparseAssembly; Dirichlet dofs are identity rows. Fixed during the
// step's Newton iterations: host elements, active set, flags, switches (extraction §5).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "matpoint/implicit/active_set.hpp"
#include "matpoint/implicit/ad_jacobian.hpp"
#include "matpoint/implicit/one_sided_boundary.hpp"
#include "matpoint/implicit/particle_newmark/inactive_mass.hpp"
#include "matpoint/implicit/particle_newmark/particle_residual.hpp"
#include "matpoint/implicit/particle_newmark/soft_stiffness.hpp"
#include "matpoint/implicit/sparse_assembly.hpp"
#include "matpoint/implicit/surface_load.hpp"
#include "matpoint/mesh/mesh.hpp"

namespace matpoint::implicit {

/// A particle foot in contact with a one-sided wall (one_sided_boundary.hpp) on its particle's host
/// element: the weights W_J with u~(x_f) = sum_J W_J u~_J (ParticleNewmarkStepper::locate_feet), the wall
/// (normal axis, outward sign), the step-start gap g, whether the tangential components are held too (no
/// slip) and the penalty stiffness k.
template <class E>
struct FootBlock {
  Index element = 0;
  Eigen::Matrix<double, E::kNodes, 1> W;
  int normal_axis = 0;
  double outward = -1.0;
  double gap = 0.0;
  bool no_slip = true;
  double stiffness = 0.0;
};

template <class E, class Material>
class ParticleNewmarkSystem {
 public:
  static constexpr int kDim = E::kDim, kNodes = E::kNodes, kDofs = kNodes * kDim;
  static constexpr int kFaceDofs = E::kNodesPerFace * kDim;

  /// What one step fixes. q has one block per active element (in set.active_elements order);
  /// soft_stiffness[k] = mu C_E of active element k (0: none); receding[k]: C_c per face of active
  /// element k (empty: none anywhere); dirichlet: one flag per dof.
  struct StepData {
    const mesh::Mesh<kDim>* mesh = nullptr;
    std::span<const Vec<kDim>> reference_nodes;  // x~ (the mesh's nodes in the uncoupled case)
    std::uint64_t reference_version = 0;         // changes whenever reference_nodes move
    const ActiveSet* set = nullptr;
    const ParticleQuadrature<E>* quadrature = nullptr;
    std::span<const Material> materials;
    std::vector<double> soft_stiffness;
    std::vector<FaceCoefficients<E>> receding;
    std::span<const char> dirichlet;
    std::vector<FaceLoad<kDim>> face_loads;  // at the step's end; faces of inactive elements are skipped
    std::vector<FaceLoad<kDim>> face_loads_at_start;  // the same faces at the step's start (the work)
    std::vector<FootBlock<E>> feet;                   // particle feet in contact with one-sided walls
    ParticleResidualOptions options;
    int gauss_points_per_direction = 3;  // soft stiffness and lumped mass (the paper's 3 x 3 for Q9)
  };

  /// Builds the blocks, and the sparse pattern when they differ from the last call's (a new active
  /// set); the pattern version, hence the solver's symbolic analysis, survives otherwise.
  void setup(StepData data);

  /// Another contact set for the same step (a re-solve round): only the feet change. They live in
  /// their host elements' blocks, so the blocks, their geometry and the pattern all stay.
  void set_feet(std::vector<FootBlock<E>> feet) {
    data_.feet = std::move(feet);
    index_feet_by_element();
  }

  /// R(u~) and, when K is not null, the Jacobian; Dirichlet rows as identity with zero residual
  /// unless `constrain` is false (then R holds the reactions there: the force the condition exerts).
  bool assemble(const Eigen::VectorXd& u, Eigen::VectorXd& R, SparseMatrix* K, bool constrain = true) const;

  [[nodiscard]] const SparseAssembly& assembly() const { return assembly_; }
  [[nodiscard]] Index dof_count() const { return assembly_.dof_count(); }

  /// The surface loads' work over the converged step u, (f(t_n, 0) + f(t_{n+1}, u)) / 2 . u: the
  /// start's load on the reset grid, the end's on the converged displacement (trapezoidal).
  [[nodiscard]] double surface_load_work(const Eigen::VectorXd& u) const;

  /// The residual and Jacobian (row-major) of active element k alone at its dofs' values u_e.
  void element_residual_and_jacobian(Index k, const double* u_e, double* r, double* K) const;
  void element_residual(Index k, const double* u_e, double* r) const;

 private:
  template <class S>
  void active_residual(Index k, const S* u, S* r) const;
  /// A foot's penalty added to its host element's block (u_e, r, K over the element's dofs,
  /// node-major): one_sided_boundary.hpp's add_foot_penalty.
  static void add_foot(const FootBlock<E>& foot, const double* u_e, double* r, double* K) {
    add_foot_penalty<kDim>(std::span<const double>(foot.W.data(), kNodes), foot.normal_axis, foot.outward,
                           foot.gap, foot.no_slip, foot.stiffness, u_e, r, K);
  }
  /// Sorts data_.feet by host element and sets first_foot_: active element k's feet are
  /// data_.feet[first_foot_[k] .. first_foot_[k + 1]).
  void index_feet_by_element();

  /// Element e's lumped node masses per unit density on reference_nodes (the inactive elements'
  /// equations (27)), computed once per element and kept while reference_version stays: on a fixed
  /// background mesh, once per run (recomputing them every step for every empty element of the
  /// mesh was a tenth of a rolling-disk run).
  const Eigen::Matrix<double, kNodes, 1>& element_lumped_mass(Index e) {
    const auto count = static_cast<std::size_t>(data_.mesh->element_count());
    if (lumped_mass_version_ != data_.reference_version || lumped_mass_.size() != count ||
        lumped_mass_nodes_ != data_.reference_nodes.data() ||
        lumped_mass_gauss_ != data_.gauss_points_per_direction) {
      lumped_mass_.assign(count, Eigen::Matrix<double, kNodes, 1>::Zero());
      lumped_mass_known_.assign(count, 0);
      lumped_mass_version_ = data_.reference_version;
      lumped_mass_nodes_ = data_.reference_nodes.data();
      lumped_mass_gauss_ = data_.gauss_points_per_direction;
    }
    const auto k = static_cast<std::size_t>(e);
    if (!lumped_mass_known_[k]) {
      lumped_mass_[k] = lumped_node_masses<E>(
          gauss_geometry<E>(gather_nodes<E>(data_.reference_nodes, data_.mesh->element_nodes(e)),
                            data_.gauss_points_per_direction, data_.mesh->element_variant(e)));
      lumped_mass_known_[k] = 1;
    }
    return lumped_mass_[k];
  }

  StepData data_;
  Index active_ = 0;
  std::vector<Eigen::Matrix<double, kNodes, 1>> lumped_mass_;  // element_lumped_mass's cache
  std::vector<char> lumped_mass_known_;
  std::uint64_t lumped_mass_version_ = 0;  // the key of the cache: version, nodes, Gauss rule
  const Vec<kDim>* lumped_mass_nodes_ = nullptr;
  int lumped_mass_gauss_ = 0;
  std::vector<std::size_t> first_foot_;  // data_.feet by active element (index_feet_by_element)
  /// The external nodal forces of `loads` (parallel to loads_'s faces) at u, node-major.
  [[nodiscard]] Eigen::VectorXd surface_load_forces(const std::vector<FaceLoad<kDim>>& loads,
                                                    const Eigen::VectorXd& u) const;

  std::vector<FaceLoad<kDim>> loads_;                    // the face blocks, after the active elements
  std::vector<FaceLoad<kDim>> loads_start_;              // the same faces at the step's start
  std::vector<FaceNodes<E>> load_nodes_;                 // their nodes in x~
  std::vector<std::array<Index, kFaceDofs>> load_dofs_;  // and their dofs (the blocks' dof lists)
  std::vector<GaussGeometry<E>> soft_geometry_;          // per active element with soft stiffness
  std::vector<double> mass_dof_;                         // per inactive-node block (one dof): its lumped mass
  SparseAssembly assembly_;
};

template <class E, class Material>
void ParticleNewmarkSystem<E, Material>::setup(StepData data) {
  data_ = std::move(data);
  const auto& mesh = *data_.mesh;
  const auto& set = *data_.set;
  active_ = static_cast<Index>(set.active_elements.size());
  std::vector<Index> offsets{0}, dofs;
  soft_geometry_.assign(static_cast<std::size_t>(active_), {});
  for (Index k = 0; k < active_; ++k) {
    const Index e = set.active_elements[static_cast<std::size_t>(k)];
    for (const Index node : mesh.element_nodes(e))
      for (int i = 0; i < kDim; ++i) dofs.push_back(node * kDim + i);
    offsets.push_back(static_cast<Index>(dofs.size()));
    if (data_.soft_stiffness[static_cast<std::size_t>(k)] > 0.0)
      soft_geometry_[static_cast<std::size_t>(k)] =
          gauss_geometry<E>(gather_nodes<E>(data_.reference_nodes, mesh.element_nodes(e)),
                            data_.gauss_points_per_direction, mesh.element_variant(e));
  }
  // Surface loads on the faces of active elements (elsewhere the body is not at the boundary).
  loads_.clear();
  loads_start_.clear();
  load_nodes_.clear();
  load_dofs_.clear();
  for (std::size_t l = 0; l < data_.face_loads.size(); ++l) {
    const FaceLoad<kDim>& load = data_.face_loads[l];
    if (!set.element_active(load.element)) continue;
    const auto nodes = mesh.element_nodes(load.element);
    FaceNodes<E> x;
    std::array<Index, kFaceDofs> face_dofs;
    int a = 0;
    const auto face = E::faces()[static_cast<std::size_t>(load.face)];  // a copy: faces() returns by value
    for (const int local : face) {
      const Index node = nodes[static_cast<std::size_t>(local)];
      x.row(a) = data_.reference_nodes[static_cast<std::size_t>(node)].transpose();
      for (int i = 0; i < kDim; ++i) face_dofs[static_cast<std::size_t>(a * kDim + i)] = node * kDim + i;
      ++a;
    }
    dofs.insert(dofs.end(), face_dofs.begin(), face_dofs.end());
    offsets.push_back(static_cast<Index>(dofs.size()));
    loads_.push_back(load);
    loads_start_.push_back(l < data_.face_loads_at_start.size() ? data_.face_loads_at_start[l] : load);
    load_nodes_.push_back(x);
    load_dofs_.push_back(face_dofs);
  }
  index_feet_by_element();  // the feet join their host elements' blocks
  // Inactive elements: the mass equations (27) of their I_ib nodes, summed per node (a row-sum
  // lumped mass), one 1 x 1 block per dof: the pattern of these rows is the diagonal alone (blocks
  // over an element's nodes would add their structural zeros to the factorisation).
  std::vector<double> node_mass(static_cast<std::size_t>(mesh.node_count()), 0.0);
  for (const Index e : set.inactive_elements) {
    const auto nodes = mesh.element_nodes(e);
    const auto& m = element_lumped_mass(e);
    for (int I = 0; I < kNodes; ++I)
      node_mass[static_cast<std::size_t>(nodes[static_cast<std::size_t>(I)])] += m[I];
  }
  mass_dof_.clear();
  for (Index node = 0; node < mesh.node_count(); ++node)
    if (set.node_active[static_cast<std::size_t>(node)] == 0)
      for (int i = 0; i < kDim; ++i) {
        dofs.push_back(node * kDim + i);
        offsets.push_back(static_cast<Index>(dofs.size()));
        mass_dof_.push_back(node_mass[static_cast<std::size_t>(node)]);
      }
  // SparseAssembly keeps the pattern, and its version (hence the solver's symbolic analysis), when
  // the blocks and Dirichlet dofs are the last step's.
  assembly_.build(mesh.node_count() * kDim, offsets, dofs, data_.dirichlet);
}

template <class E, class Material>
void ParticleNewmarkSystem<E, Material>::index_feet_by_element() {
  auto& feet = data_.feet;
  std::stable_sort(feet.begin(), feet.end(),
                   [](const FootBlock<E>& a, const FootBlock<E>& b) { return a.element < b.element; });
  const std::vector<Index>& active = data_.set->active_elements;  // ascending
  first_foot_.assign(static_cast<std::size_t>(active_) + 1, 0);
  for (const FootBlock<E>& foot : feet) {
    const auto k = std::lower_bound(active.begin(), active.end(), foot.element) - active.begin();
    if (k == static_cast<std::ptrdiff_t>(active.size()) ||
        active[static_cast<std::size_t>(k)] != foot.element)
      throw std::logic_error("ParticleNewmarkSystem: a foot's host element is not active");
    ++first_foot_[static_cast<std::size_t>(k) + 1];
  }
  for (std::size_t k = 0; k < active.size(); ++k) first_foot_[k + 1] += first_foot_[k];
}

template <class E, class Material>
template <class S>
void ParticleNewmarkSystem<E, Material>::active_residual(Index k, const S* u, S* r) const {
  const auto& q = *data_.quadrature;
  static const FaceCoefficients<E> kNone{};
  const FaceCoefficients<E>& receding =
      data_.receding.empty() ? kNone : data_.receding[static_cast<std::size_t>(k)];
  add_particle_residual<E>(q, q.begin[static_cast<std::size_t>(k)], q.begin[static_cast<std::size_t>(k) + 1],
                           data_.materials.data(), receding, data_.options, u, r);
  const double soft = data_.soft_stiffness[static_cast<std::size_t>(k)];
  if (soft > 0.0) add_soft_stiffness_residual<E>(soft_geometry_[static_cast<std::size_t>(k)], soft, u, r);
}

template <class E, class Material>
double ParticleNewmarkSystem<E, Material>::surface_load_work(const Eigen::VectorXd& u) const {
  if (loads_.empty()) return 0.0;
  return 0.5 *
         (surface_load_forces(loads_start_, Eigen::VectorXd::Zero(u.size())) + surface_load_forces(loads_, u))
             .dot(u);
}

template <class E, class Material>
Eigen::VectorXd ParticleNewmarkSystem<E, Material>::surface_load_forces(
    const std::vector<FaceLoad<kDim>>& loads, const Eigen::VectorXd& u) const {
  Eigen::VectorXd force = Eigen::VectorXd::Zero(dof_count());
  for (std::size_t f = 0; f < loads.size(); ++f) {
    const auto& dofs = load_dofs_[f];
    std::array<double, kFaceDofs> u_f, r_f{};
    for (std::size_t i = 0; i < dofs.size(); ++i) u_f[i] = u[dofs[i]];
    add_surface_load_residual<E>(load_nodes_[f], loads[f], u_f.data(), r_f.data());
    for (std::size_t i = 0; i < dofs.size(); ++i) force[dofs[i]] -= r_f[i];
  }
  return force;
}

template <class E, class Material>
void ParticleNewmarkSystem<E, Material>::element_residual_and_jacobian(Index k, const double* u_e, double* r,
                                                                       double* K) const {
  residual_and_jacobian<kDofs>(
      u_e, [&](const auto* u, auto* res) { active_residual(k, u, res); }, r, K);
}

template <class E, class Material>
void ParticleNewmarkSystem<E, Material>::element_residual(Index k, const double* u_e, double* r) const {
  residual_only<kDofs>(
      u_e, [&](const double* u, double* res) { active_residual(k, u, res); }, r);
}

template <class E, class Material>
bool ParticleNewmarkSystem<E, Material>::assemble(const Eigen::VectorXd& u, Eigen::VectorXd& R,
                                                  SparseMatrix* K, bool constrain) const {
  assembly_.assemble(
      [&](Index b, std::span<const Index> dofs, double* r, double* k) {
        if (b < active_) {
          std::array<double, kDofs> u_e;
          for (int i = 0; i < kDofs; ++i)
            u_e[static_cast<std::size_t>(i)] = u[dofs[static_cast<std::size_t>(i)]];
          if (k != nullptr)
            element_residual_and_jacobian(b, u_e.data(), r, k);
          else
            element_residual(b, u_e.data(), r);
          for (std::size_t f = first_foot_[static_cast<std::size_t>(b)];
               f < first_foot_[static_cast<std::size_t>(b) + 1]; ++f)
            add_foot(data_.feet[f], u_e.data(), r, k);
          return;
        }
        const auto face_count = static_cast<Index>(loads_.size());
        if (b < active_ + face_count) {
          const auto f = static_cast<std::size_t>(b - active_);
          std::array<double, kFaceDofs> u_f;
          for (int i = 0; i < kFaceDofs; ++i)
            u_f[static_cast<std::size_t>(i)] = u[dofs[static_cast<std::size_t>(i)]];
          const auto residual = [&](const auto* uf, auto* rf) {
            add_surface_load_residual<E>(load_nodes_[f], loads_[f], uf, rf);
          };
          if (k != nullptr)
            residual_and_jacobian<kFaceDofs>(u_f.data(), residual, r, k);
          else
            residual_only<kFaceDofs>(u_f.data(), residual, r);
          return;
        }
        // (27): r = m u for one dof of an I_ib node, dr/du = m.
        const double m = mass_dof_[static_cast<std::size_t>(b - active_ - face_count)];
        r[0] = m * u[dofs[0]];
        if (k != nullptr) k[0] = m;
      },
      R, K, constrain);
  return R.allFinite();
}

}  // namespace matpoint::implicit
