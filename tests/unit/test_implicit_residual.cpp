// Element residuals of Aulisa & Capodaglio's implicit MPM (implicit/particle_newmark/).
//   AT-2 (extraction §12; the authors ran the same check): particles at the 3 x 3 Gauss points with
//   m_p = rho0 w_g det J_g reproduce a standard total-Lagrangian FEM residual and Jacobian to
//   round-off. The FEM side is written here from the textbook formulas (Bonet & Wood, Nonlinear
//   Continuum Mechanics for FEA, 2nd ed., eq. (6.28) for P of the compressible neo-Hookean solid and
//   §9.4 for the consistent tangent dP/dF), not with the code under test.
//   AT-3: the AD Jacobian agrees with central finite differences of the residual, with the soft
//   stiffness (26) and the receding correction (A3) active, for both gradient choices of A24.
//   Flags M_E (paper §3.3: interior element 9, an element surrounded by empty ones 1), the lumped
//   node masses of eq. (27) (extraction §5.4: corner A/36, mid-side A/9, centre 4A/9), and the
//   receding correction's zero normal derivative (extraction §8: f'(-1) = 0 for the quadratic
//   through the corrected nodes).
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/implicit/ad_jacobian.hpp"
#include "matpoint/implicit/particle_newmark/element_flags.hpp"
#include "matpoint/implicit/particle_newmark/inactive_mass.hpp"
#include "matpoint/implicit/particle_newmark/particle_residual.hpp"
#include "matpoint/implicit/particle_newmark/soft_stiffness.hpp"
#include "matpoint/material/neo_hookean.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;

constexpr double kRho0 = 1000.0;
const NeoHookean kMaterial{kRho0, 2.0e6, 1.0e6};
constexpr double kInertia = 1.0 / (0.3 * 0.01 * 0.01);  // 1 / (beta dt^2), beta = 0.3, dt = 0.01

/// A distorted element: the reference nodes, shifted (curved sides for Q9).
template <class E>
NodeMatrix<E> distorted_nodes() {
  NodeMatrix<E> x = 0.5 * E::reference_nodes();
  for (int i = 0; i < E::kNodes; ++i)
    for (int a = 0; a < E::kDim; ++a) x(i, a) += 0.04 * std::sin(1.3 * i + 2.1 * a);
  return x;
}

template <int D>
Vec<D> known_term() {
  Vec<D> k = Vec<D>::Constant(0.3);
  k[D - 1] = 9.81 - 2.0;  // -v/(beta dt) - (1 - 2 beta)/(2 beta) a minus b: some constant
  return k;
}

template <class E>
std::array<double, E::kNodes * E::kDim> displacement(double scale) {
  std::array<double, E::kNodes * E::kDim> u;
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = scale * std::sin(0.7 * static_cast<double>(i) + 0.4);
  return u;
}

/// Total-Lagrangian FEM residual and tangent on the Gauss points (Bonet & Wood): with F = I + grad_X u,
///   P = mu (F - F^-T) + lambda ln J F^-T,
///   dP_iJ/dF_kL = mu d_ik d_JL + (mu - lambda ln J) Fi_Li Fi_Jk + lambda Fi_Ji Fi_Lk  (Fi = F^-1),
///   r_Ii = sum_g w_g det J_g [rho0 (c u_g + k)_i N_I + P_iJ dN_I/dX_J],
/// plus the consistent mass rho0 c N_I N_K d_ik in the tangent.
template <class E>
void fem_residual(const NodeMatrix<E>& X, const double* u, Eigen::VectorXd& r, Eigen::MatrixXd& K) {
  constexpr int n = E::kNodes, D = E::kDim;
  const auto& rule = mesh::gauss_rule<E>(3);
  r.setZero(n * D);
  K.setZero(n * D, n * D);
  const double lambda = kMaterial.lambda, mu = kMaterial.mu;
  for (std::size_t g = 0; g < rule.points.size(); ++g) {
    const Eigen::Matrix<double, n, 1> N = E::values(rule.points[g]);
    const Eigen::Matrix<double, n, D> dxi = E::gradients(rule.points[g]);
    const Mat<D> jac = X.transpose() * dxi;
    const double w = rule.weights[g] * jac.determinant();
    const Eigen::Matrix<double, n, D> G = dxi * jac.inverse();
    Mat<D> F = Mat<D>::Identity();
    Vec<D> ug = Vec<D>::Zero();
    for (int I = 0; I < n; ++I)
      for (int i = 0; i < D; ++i) {
        ug[i] += N[I] * u[I * D + i];
        for (int J = 0; J < D; ++J) F(i, J) += u[I * D + i] * G(I, J);
      }
    const Mat<D> Fi = F.inverse();
    const double lnJ = std::log(F.determinant());
    const Mat<D> P = mu * (F - Fi.transpose()) + lambda * lnJ * Fi.transpose();
    const Vec<D> inertia = kRho0 * (kInertia * ug + known_term<D>());
    for (int I = 0; I < n; ++I)
      for (int i = 0; i < D; ++i) {
        r[I * D + i] += w * (inertia[i] * N[I] + P.row(i).dot(G.row(I)));
        for (int Kn = 0; Kn < n; ++Kn)
          for (int k = 0; k < D; ++k) {
            double a = i == k ? kRho0 * kInertia * N[I] * N[Kn] : 0.0;
            for (int J = 0; J < D; ++J)
              for (int L = 0; L < D; ++L) {
                const double A = (i == k && J == L ? mu : 0.0) + (mu - lambda * lnJ) * Fi(L, i) * Fi(J, k) +
                                 lambda * Fi(J, i) * Fi(L, k);
                a += G(I, J) * A * G(Kn, L);
              }
            K(I * D + i, Kn * D + k) += w * a;
          }
      }
  }
}

template <class E>
void check_particles_at_gauss_points_reproduce_fem() {
  constexpr int n = E::kNodes, D = E::kDim, N = n * D;
  const NodeMatrix<E> X = distorted_nodes<E>();
  const auto& rule = mesh::gauss_rule<E>(3);
  ParticleQuadrature<E> q;
  for (std::size_t g = 0; g < rule.points.size(); ++g) {
    const double w = rule.weights[g] * (X.transpose() * E::gradients(rule.points[g])).determinant();
    q.add(static_cast<Index>(g), rule.points[g], X, 0, kRho0 * w, w, 0, Mat<D>::Identity(), known_term<D>(),
          0);
  }
  q.close_block();
  const auto u = displacement<E>(0.03);
  const ParticleResidualOptions options{kInertia, true};
  const FaceCoefficients<E> none{};
  std::array<double, N> r;
  std::array<double, N * N> K;
  residual_and_jacobian<N>(
      u.data(),
      [&](const auto* us, auto* rs) {
        add_particle_residual<E>(q, 0, q.blocks() > 0 ? q.begin[1] : 0, &kMaterial, none, options, us, rs);
      },
      r.data(), K.data());
  Eigen::VectorXd r_fem;
  Eigen::MatrixXd K_fem;
  fem_residual<E>(X, u.data(), r_fem, K_fem);
  const Eigen::Map<const Eigen::VectorXd> r_mpm(r.data(), N);
  const Eigen::Map<const Eigen::Matrix<double, N, N, Eigen::RowMajor>> K_mpm(K.data());
  EXPECT_LT((r_mpm - r_fem).norm(), 1e-12 * r_fem.norm()) << E::kName;
  EXPECT_LT((K_mpm - K_fem).norm(), 1e-12 * K_fem.norm()) << E::kName;
}

TEST(ImplicitResidual, ParticlesAtGaussPointsReproduceTotalLagrangianFemQ4) {
  check_particles_at_gauss_points_reproduce_fem<mesh::Q4>();
}
TEST(ImplicitResidual, ParticlesAtGaussPointsReproduceTotalLagrangianFemQ9) {
  check_particles_at_gauss_points_reproduce_fem<mesh::Q9>();
}
TEST(ImplicitResidual, ParticlesAtGaussPointsReproduceTotalLagrangianFemHex8) {
  check_particles_at_gauss_points_reproduce_fem<mesh::Hex8>();
}

/// AT-3 on one Q9 element: 9 particles with F^n != I, soft stiffness, receding faces 0 and 3 (a
/// corner shared by both), half the particles switched.
void check_ad_jacobian_matches_differences(bool receding_in_gradient) {
  using E = mesh::Q9;
  constexpr int N = 18;
  const NodeMatrix<E> X = distorted_nodes<E>();
  ParticleQuadrature<E> q;
  for (int p = 0; p < 9; ++p) {
    const Vec<2> xi(-0.8 + 0.19 * p, 0.7 - 0.17 * p);
    Mat<2> Fn;
    Fn << 1.05, 0.02 * p, -0.03, 0.97;
    q.add(p, xi, X, 0, 0.02, 2e-5, 0, Fn, Vec<2>(0.4, -9.0), p % 2 == 0 ? 0b1001u : 0u);
  }
  q.close_block();
  const FaceCoefficients<E> receding{0.5, 0.0, 0.0, 0.3};
  const ParticleResidualOptions options{kInertia, receding_in_gradient};
  const GaussGeometry<E> soft = gauss_geometry<E>(X, 3, 0);
  const double mu_ce = kMaterial.mu * 1e-2;
  const auto residual = [&](const auto* us, auto* rs) {
    add_particle_residual<E>(q, 0, 9, &kMaterial, receding, options, us, rs);
    add_soft_stiffness_residual<E>(soft, mu_ce, us, rs);
  };
  const auto u = displacement<E>(0.02);
  std::array<double, N> r;
  std::array<double, N * N> K;
  residual_and_jacobian<N>(u.data(), residual, r.data(), K.data());
  const double h = 1e-6;
  double max_entry = 0.0, max_error = 0.0;
  for (int j = 0; j < N; ++j) {
    auto up = u, um = u;
    up[static_cast<std::size_t>(j)] += h;
    um[static_cast<std::size_t>(j)] -= h;
    std::array<double, N> rp, rm;
    residual_only<N>(up.data(), residual, rp.data());
    residual_only<N>(um.data(), residual, rm.data());
    for (int i = 0; i < N; ++i) {
      const double fd = (rp[static_cast<std::size_t>(i)] - rm[static_cast<std::size_t>(i)]) / (2.0 * h);
      max_error = std::max(max_error, std::abs(fd - K[static_cast<std::size_t>(i * N + j)]));
      max_entry = std::max(max_entry, std::abs(K[static_cast<std::size_t>(i * N + j)]));
    }
  }
  EXPECT_LT(max_error, 1e-6 * max_entry)
      << "max |K_AD - K_FD| = " << max_error << ", max |K| = " << max_entry;
  // The receding correction makes K nonsymmetric (extraction §6).
  const Eigen::Map<const Eigen::Matrix<double, N, N, Eigen::RowMajor>> Km(K.data());
  EXPECT_GT((Km - Km.transpose()).norm(), 1e-6 * Km.norm());
}

TEST(ImplicitResidual, AdJacobianMatchesCentralDifferencesWithSoftStiffnessAndReceding) {
  check_ad_jacobian_matches_differences(true);
  check_ad_jacobian_matches_differences(false);
}

TEST(ImplicitResidual, AdJacobianMatchesCentralDifferencesHex8) {
  // AT-3 in 3-D: 8 particles with F^n != I in a distorted Hex8, soft stiffness on.
  using E = mesh::Hex8;
  constexpr int N = 24;
  const NodeMatrix<E> X = distorted_nodes<E>();
  ParticleQuadrature<E> q;
  for (int p = 0; p < 8; ++p) {
    const Vec<3> xi(-0.7 + 0.2 * p, 0.6 - 0.15 * p, 0.1 * p - 0.3);
    Mat<3> Fn = Mat<3>::Identity();
    Fn(0, 1) = 0.02 * p, Fn(2, 0) = -0.03, Fn(1, 1) = 0.97;
    q.add(p, xi, X, 0, 0.02, 2e-5, 0, Fn, Vec<3>(0.4, 0.1, -9.0), 0);
  }
  q.close_block();
  const ParticleResidualOptions options{kInertia, true};
  const GaussGeometry<E> soft = gauss_geometry<E>(X, 3, 0);
  const FaceCoefficients<E> none{};
  const auto residual = [&](const auto* us, auto* rs) {
    add_particle_residual<E>(q, 0, 8, &kMaterial, none, options, us, rs);
    add_soft_stiffness_residual<E>(soft, kMaterial.mu * 1e-2, us, rs);
  };
  const auto u = displacement<E>(0.02);
  std::array<double, N> r;
  std::array<double, N * N> K;
  residual_and_jacobian<N>(u.data(), residual, r.data(), K.data());
  const double h = 1e-6;
  double max_entry = 0.0, max_error = 0.0;
  for (int j = 0; j < N; ++j) {
    auto up = u, um = u;
    up[static_cast<std::size_t>(j)] += h;
    um[static_cast<std::size_t>(j)] -= h;
    std::array<double, N> rp, rm;
    residual_only<N>(up.data(), residual, rp.data());
    residual_only<N>(um.data(), residual, rm.data());
    for (int i = 0; i < N; ++i) {
      const double fd = (rp[static_cast<std::size_t>(i)] - rm[static_cast<std::size_t>(i)]) / (2.0 * h);
      max_error = std::max(max_error, std::abs(fd - K[static_cast<std::size_t>(i * N + j)]));
      max_entry = std::max(max_entry, std::abs(K[static_cast<std::size_t>(i * N + j)]));
    }
  }
  EXPECT_LT(max_error, 1e-6 * max_entry)
      << "max |K_AD - K_FD| = " << max_error << ", max |K| = " << max_entry;
}

TEST(ImplicitResidual, RecedingCorrectionWithUnitCoefficientHasZeroNormalDerivative) {
  // u(eta) quadratic along each line normal to face 0 (eta = -1): after the correction with
  // C_c = 1 the quadratic through (u*_face, u_mid, u_far) has f'(-1) = (-3 f(-1) + 4 f(0) - f(1)) / 2 = 0.
  using E = mesh::Q9;
  const auto ref = E::reference_nodes();
  std::array<double, 18> u;
  for (int I = 0; I < 9; ++I) {
    const double xi = ref(I, 0), eta = ref(I, 1);
    u[static_cast<std::size_t>(2 * I)] = 0.3 + 0.2 * eta + 0.7 * eta * eta + 0.1 * xi;
    u[static_cast<std::size_t>(2 * I + 1)] = -0.1 * eta + 0.4 * eta * eta * xi;
  }
  apply_receding_correction<E>(0b0001u, FaceCoefficients<E>{1.0, 0.0, 0.0, 0.0}, u.data());
  for (const auto& [a, far, mid] : RecedingStencil<E>::kTriples[0])
    for (int i = 0; i < 2; ++i) {
      const double f_face = u[static_cast<std::size_t>(2 * a + i)],
                   f_mid = u[static_cast<std::size_t>(2 * mid + i)],
                   f_far = u[static_cast<std::size_t>(2 * far + i)];
      EXPECT_NEAR(-3.0 * f_face + 4.0 * f_mid - f_far, 0.0, 1e-14);
    }
  // C_c = 0 restores the Dirichlet values (u unchanged).
  std::array<double, 18> v{}, w{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = w[i] = std::cos(static_cast<double>(i));
  apply_receding_correction<E>(0b1111u, FaceCoefficients<E>{0.0, 0.0, 0.0, 0.0}, v.data());
  EXPECT_EQ(v, w);
}

TEST(ImplicitResidual, RecedingSwitchIsOnForParticlesMovingAwayFromTheFace) {
  using E = mesh::Q9;
  const Eigen::Matrix<double, 9, 2> x = E::reference_nodes();
  const FaceCoefficients<E> bottom{0.5, 0.0, 0.0, 0.0};
  EXPECT_EQ(receding_switches<E>(x, bottom, Vec<2>(0.3, 1.0)), 1u);   // moving up, away from eta = -1
  EXPECT_EQ(receding_switches<E>(x, bottom, Vec<2>(0.3, -1.0)), 0u);  // approaching
  const FaceCoefficients<E> right{0.0, 0.5, 0.0, 0.0};
  EXPECT_EQ(receding_switches<E>(x, right, Vec<2>(-1.0, 0.0)), 2u);  // moving left, away from xi = +1
}

TEST(ImplicitResidual, LumpedNodeMassesOfQ9AreTheRowSums) {
  // Extraction §5.4: int N_I over a straight Q9 element of area A: corners A/36, mid-sides A/9,
  // centre 4A/9 (Simpson's weights 1/6, 4/6, 1/6 in each direction).
  using E = mesh::Q9;
  NodeMatrix<E> x = E::reference_nodes();
  x.col(0) *= 1.5;  // 3 x 2 rectangle, A = 6
  const auto m = lumped_node_masses<E>(gauss_geometry<E>(x, 3, 0));
  const double A = 6.0;
  for (int I = 0; I < 4; ++I) EXPECT_NEAR(m[I], A / 36.0, 1e-13);
  for (int I = 4; I < 8; ++I) EXPECT_NEAR(m[I], A / 9.0, 1e-13);
  EXPECT_NEAR(m[8], 4.0 * A / 9.0, 1e-13);
}

TEST(ImplicitResidual, ElementFlagsFollowThePaperRuleAndTheCodeVariant) {
  // 5 x 5 Q9 elements. Case 1: particles only in the centre element (id 12): it is surrounded by
  // empty elements, so only its centre node is unshared: M_E = 1 (paper §3.3). Case 2: particles in
  // the central 3 x 3 block: the middle element is fully surrounded (M_E = 9, C_E = 0), an edge
  // element of the block shares one face (3 nodes) with empty elements (M_E = 6), a corner
  // element two faces (5 nodes, M_E = 4).
  const auto mesh = mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 5, 5),
                                               mesh::AxisSpacing::uniform(0, 5, 5));
  std::vector<Index> host{12, 12};
  auto set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
  ASSERT_EQ(set.active_elements, std::vector<Index>{12});
  EXPECT_EQ(element_flags(set, 9, mesh.connectivity, FlagRule::Paper), std::vector<int>{1});
  host = {6, 7, 8, 11, 12, 13, 16, 17, 18};
  set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
  const auto flags = element_flags(set, 9, mesh.connectivity, FlagRule::Paper);
  EXPECT_EQ(flags, (std::vector<int>{4, 6, 4, 6, 9, 6, 4, 6, 4}));
  const SoftStiffnessTable table{{{5, 1e-2}, {9, 1e-6}}};  // the paper's eq. (50) form
  EXPECT_TRUE(table.validate().empty());
  EXPECT_EQ(soft_stiffness_factors(flags, table, FlagRule::Paper),
            (std::vector<double>{1e-2, 1e-6, 1e-2, 1e-6, 0.0, 1e-6, 1e-2, 1e-6, 1e-2}));
  // Code variant (A13): nodes on a Dirichlet-tagged contact plane (the mesh's bottom side) also
  // lower M_E. Block of elements 1-3 (bottom row) and 6-8 above them: element 2 (bottom middle) has
  // active neighbours on three sides and the plane below, so the paper rule gives 9 and the code
  // rule 9 - 3 = 6 (its three bottom nodes are marked). An element alone (M_E = 1) gets no soft
  // stiffness under the code rule (M_E < 2).
  std::vector<char> marked(static_cast<std::size_t>(mesh.node_count()), 0);
  for (const Index node : mesh.node_sets.at("bottom")) marked[static_cast<std::size_t>(node)] = 1;
  host = {1, 2, 3, 6, 7, 8};
  set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
  const auto paper = element_flags(set, 9, mesh.connectivity, FlagRule::Paper);
  const auto code = element_flags(set, 9, mesh.connectivity, FlagRule::Code, marked);
  EXPECT_EQ(paper[1], 9);
  EXPECT_EQ(code[1], 6);
  host = {12};
  set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
  EXPECT_EQ(soft_stiffness_factors(element_flags(set, 9, mesh.connectivity, FlagRule::Code, marked), table,
                                   FlagRule::Code),
            std::vector<double>{0.0});
  EXPECT_FALSE((SoftStiffnessTable{{{5, 1e-6}, {9, 1e-2}}}).validate().empty());  // increasing C_E
}

}  // namespace
