// Finite element bodies of an implicit run (Aulisa & Capodaglio §4, eqs. (36)-(43), (46); extraction
// §5.5): mesh elements that carry a total-Lagrangian solid instead of background grid. Their Gauss
// points enter the same assembly as the MPM particles (implicit/particle_newmark/): a Gauss point
// is a quadrature point whose host element and local coordinates never change, with
//   mass     m_g = rho_inertia w_g det J_g(X),  volume V0_g = w_g det J_g(X)   (reference measure)
//   F_g      = (I + grad~ u~) F_g^n, grad~ on the body's nodes at the step start x~ = X + u^n
//            (then F_g is the total-Lagrangian I + grad_X u, eqs. (39)-(40))
//   stress   V0 tau grad_x N_I = integral of P : grad_X N_I dV0 (the physical form of eq. (41), A2)
//   inertia  m_g sum_J N_J a_J N_I (consistent mass) with the nodal Newmark of eq. (46):
//            a_J = u~_J / (beta dt^2) - v_J^n / (beta dt) - (1 - 2 beta) / (2 beta) a_J^n.
// rho_inertia is the material's density (default), or 1 (the authors' code, whose FEM inertia term
// has no density: extraction A2, "inertia": "unit_density"). Gravity acts on the body unless the
// input switches it off (both of the paper's coupled tests do).
// The nodes of a body keep u, v, a from step to step (an FE body's grid is never reset, eq. (7)).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/implicit/element_geometry.hpp"
#include "matpoint/implicit/implicit_material.hpp"
#include "matpoint/implicit/particle_newmark/particle_quadrature.hpp"
#include "matpoint/mesh/mesh.hpp"

namespace matpoint::fem {

/// The Gauss rule of an FE body's elements: exact for the consistent mass matrix on undistorted
/// elements (2 x 2 for Q4, 3 x 3 for Q9 as the paper, 2 x 2 x 2 for Hex8; degree 2 for T3, 4 for T6).
template <class E>
const mesh::QuadratureRule<E::kDim>& fe_gauss_rule() {
  if constexpr (E::kSimplex)
    return mesh::gauss_rule<E>(E::kNodes == 3 ? 2 : 4);
  else
    return mesh::gauss_rule<E>(E::kNodes == 9 ? 3 : 2);
}

/// One FE body as the input gives it: its elements (mesh element ids), material and switches.
struct FeBodyDefinition {
  std::vector<Index> elements;
  int material = 0;
  double density = 0.0;          // rho of the material: the body force is rho b per unit volume
  double inertia_density = 0.0;  // rho, or 1 (A2's compatibility mode): the inertia's density
  bool gravity = true;
};

/// All FE bodies of a run: Gauss-point state element by element, and nodal Newmark state.
template <class E>
class FeBodies {
 public:
  static constexpr int D = E::kDim;

  FeBodies() = default;
  /// Gauss points at the elements' rule points, measured on the mesh's (undeformed) nodes.
  FeBodies(const mesh::Mesh<D>& mesh, const std::vector<FeBodyDefinition>& bodies);

  [[nodiscard]] bool empty() const { return elements_.empty(); }
  /// Per mesh element: 1 where it belongs to an FE body.
  [[nodiscard]] const std::vector<char>& element_mask() const { return element_mask_; }
  /// Per mesh node: 1 where it belongs to an FE element (interface nodes included, A19).
  [[nodiscard]] const std::vector<char>& node_mask() const { return node_mask_; }
  /// FE element index of mesh element e (-1: background).
  [[nodiscard]] Index fe_element(Index e) const { return fe_index_[static_cast<std::size_t>(e)]; }
  [[nodiscard]] Index element_count() const { return static_cast<Index>(elements_.size()); }
  [[nodiscard]] Index mesh_element(Index k) const { return elements_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] int body_of(Index k) const { return body_[static_cast<std::size_t>(k)]; }

  /// Appends FE element k's Gauss points to the current block of q (the caller closes it): x~ its
  /// nodes at the step start, the known part of the acceleration from the nodal predictor, minus
  /// the body force where the body takes gravity. Gauss point g is stored as particle -1 - g.
  void add_quadrature(Index k, const implicit::NodeMatrix<E>& x_reference, std::span<const Index> nodes,
                      mesh::ElementVariant variant, const implicit::NewmarkCoefficients& c,
                      bool static_analysis, const Vec<D>& gravity, implicit::ParticleQuadrature<E>& q) const;

  /// a^0 at the nodes consistent with the body force b at rest (A17's "body_force" option): M a = f
  /// holds with a_I = s b for an unstressed body (s = rho / rho_inertia, 0 without gravity).
  void start_from_body_force(const mesh::Mesh<D>& mesh, const Vec<D>& b) {
    const auto per = static_cast<std::size_t>(points_per_element());
    for (Index k = 0; k < element_count(); ++k)
      for (const Index n : mesh.element_nodes(mesh_element(k)))
        acceleration[static_cast<std::size_t>(n)] = body_force_scale[static_cast<std::size_t>(k) * per] * b;
  }

  /// Gauss point index of a quadrature entry that add_quadrature() stored (particle < 0).
  [[nodiscard]] static Index gauss_point_of(Index particle) { return -1 - particle; }

  /// The converged step at Gauss point g: F_g <- H F_g, and its Cauchy stress (Hooke's on
  /// sym(F - 1) with small_strain, as the residual).
  template <class Material>
  void commit_gauss_point(Index g, const Mat<D>& H, const Material& material, double dt, bool small_strain);

  /// The nodal Newmark update (46) of every FE node from the converged u~ (node-major), then
  /// u <- u + u~ and x~ <- X + u for those nodes.
  void commit_nodes(const Eigen::VectorXd& u, const implicit::NewmarkParameters& newmark, double dt,
                    bool static_analysis, std::span<const Vec<D>> undeformed, std::vector<Vec<D>>& reference);

  // Nodal state (per mesh node; zero away from FE bodies).
  std::vector<Vec<D>> displacement, velocity, acceleration;
  // Gauss-point state (element-major: element k's points are [k * rule size, (k + 1) * rule size)).
  std::vector<Mat<D>> F, stress;
  std::vector<double> stress_zz, mass, volume0;
  std::vector<int> material;
  /// Per Gauss point: rho / rho_inertia where the body takes the body force (the residual's
  /// m_g (a - s b) then holds rho V0 b whatever the inertia's density), 0 where it does not.
  std::vector<double> body_force_scale;

  [[nodiscard]] static int points_per_element() { return static_cast<int>(fe_gauss_rule<E>().points.size()); }

 private:
  std::vector<Index> elements_, fe_index_;
  std::vector<int> body_;
  std::vector<char> element_mask_, node_mask_;
};

template <class E>
FeBodies<E>::FeBodies(const mesh::Mesh<D>& mesh, const std::vector<FeBodyDefinition>& bodies) {
  const auto nodes = static_cast<std::size_t>(mesh.node_count());
  element_mask_.assign(static_cast<std::size_t>(mesh.element_count()), 0);
  fe_index_.assign(static_cast<std::size_t>(mesh.element_count()), -1);
  node_mask_.assign(nodes, 0);
  displacement.assign(nodes, Vec<D>::Zero());
  velocity.assign(nodes, Vec<D>::Zero());
  acceleration.assign(nodes, Vec<D>::Zero());
  const auto& rule = fe_gauss_rule<E>();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (const Index e : bodies[b].elements) {
      if (element_mask_[static_cast<std::size_t>(e)] != 0) continue;  // two bodies claiming one element
      element_mask_[static_cast<std::size_t>(e)] = 1;
      fe_index_[static_cast<std::size_t>(e)] = static_cast<Index>(elements_.size());
      elements_.push_back(e);
      body_.push_back(static_cast<int>(b));
      const auto element_nodes = mesh.element_nodes(e);
      for (const Index n : element_nodes) node_mask_[static_cast<std::size_t>(n)] = 1;
      const auto X = implicit::gather_nodes<E>(mesh.nodes, element_nodes);
      for (std::size_t g = 0; g < rule.points.size(); ++g) {
        double det = 0.0;
        implicit::physical_gradients<E>(X, rule.points[g], mesh.element_variant(e), &det);
        const double v0 = rule.weights[g] * det;
        volume0.push_back(v0);
        mass.push_back(bodies[b].inertia_density * v0);
        material.push_back(bodies[b].material);
        body_force_scale.push_back(bodies[b].gravity ? bodies[b].density / bodies[b].inertia_density : 0.0);
        F.push_back(Mat<D>::Identity());
        stress.push_back(Mat<D>::Zero());
        stress_zz.push_back(0.0);
      }
    }
}

template <class E>
void FeBodies<E>::add_quadrature(Index k, const implicit::NodeMatrix<E>& x_reference,
                                 std::span<const Index> nodes, mesh::ElementVariant variant,
                                 const implicit::NewmarkCoefficients& c, bool static_analysis,
                                 const Vec<D>& body_force, implicit::ParticleQuadrature<E>& q) const {
  const auto& rule = fe_gauss_rule<E>();
  const auto per = static_cast<Index>(rule.points.size());
  for (Index i = 0; i < per; ++i) {
    const Index g = k * per + i;
    const auto gs = static_cast<std::size_t>(g);
    const Vec<D>& xi = rule.points[static_cast<std::size_t>(i)];
    Vec<D> known = Vec<D>::Zero();
    if (!static_analysis) {  // the nodal predictor (46) interpolated: sum_J N_J known(v_J, a_J)
      const auto N = E::values(xi, variant);
      for (int J = 0; J < E::kNodes; ++J) {
        const auto n = static_cast<std::size_t>(nodes[static_cast<std::size_t>(J)]);
        known += N[J] * c.known<D>(velocity[n], acceleration[n]);
      }
    }
    known -= body_force_scale[gs] * body_force;
    q.add(-1 - g, xi, x_reference, variant, mass[gs], volume0[gs], material[gs], F[gs], known, 0u, nullptr);
  }
}

template <class E>
template <class Material>
void FeBodies<E>::commit_gauss_point(Index g, const Mat<D>& H, const Material& m, double dt,
                                     bool small_strain) {
  const auto gs = static_cast<std::size_t>(g);
  if (small_strain) {  // additive, as the residual (implicit/particle_newmark/particle_residual.hpp)
    F[gs] += H - Mat<D>::Identity();
    const Mat<D> eps = 0.5 * (F[gs] + F[gs].transpose()) - Mat<D>::Identity();
    stress[gs] = m.lambda * eps.trace() * Mat<D>::Identity() + 2.0 * m.mu * eps;
    stress_zz[gs] = m.lambda * eps.trace();
    return;
  }
  F[gs] = H * F[gs];
  double sigma_zz = 0.0;
  stress[gs] = implicit::updated_stress_of<D>(m, F[gs], nullptr, sigma_zz, dt);
  stress_zz[gs] = sigma_zz;
}

template <class E>
void FeBodies<E>::commit_nodes(const Eigen::VectorXd& u, const implicit::NewmarkParameters& newmark,
                               double dt, bool static_analysis, std::span<const Vec<D>> undeformed,
                               std::vector<Vec<D>>& reference) {
  const implicit::NewmarkCoefficients c(newmark, dt);
  for (std::size_t n = 0; n < node_mask_.size(); ++n) {
    if (node_mask_[n] == 0) continue;
    const Vec<D> du = u.template segment<D>(static_cast<Index>(n) * D);
    if (!static_analysis) {  // (46)
      const Vec<D> a_new = c.displacement * du + c.known<D>(velocity[n], acceleration[n]);
      velocity[n] += dt * ((1.0 - newmark.gamma) * acceleration[n] + newmark.gamma * a_new);
      acceleration[n] = a_new;
    }
    displacement[n] += du;
    reference[n] = undeformed[n] + displacement[n];
  }
}

}  // namespace matpoint::fem
