// The Galerkin meshfree point residual and step (Iaconeta et al. 2017 §4.2, Algorithm 2;
// extraction §9.2 U-2, U-7): the chain-rule Jacobian K = B^T (df/dz) B against central differences
// of the residual, a rigid translation carrying no stress, and free fall under gravity, which
// Newmark's average acceleration integrates exactly (u = g t^2 / 2 at every node and point).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "matpoint/implicit/meshfree/meshfree_stepper.hpp"
#include "matpoint/material/neo_hookean.hpp"

namespace matpoint {
namespace {

/// A jittered 5 x 5 node patch and the MLS stencil of a point inside it.
struct Patch {
  std::vector<Vec<2>> nodes;
  MeshfreeStencils<2> stencil;
  Patch() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.2, 0.2);
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) nodes.emplace_back(0.1 * (i + u(rng)), 0.1 * (j + u(rng)));
    MeshfreeParameters par;
    par.spacing = 0.1;
    build_meshfree_stencils<2>(std::vector<Vec<2>>{Vec<2>(0.21, 0.17)}, nodes, par, stencil);
  }
  implicit::MeshfreePointData<2> data() const {
    implicit::MeshfreePointData<2> q;
    const auto n = static_cast<std::size_t>(stencil.offset[1]);
    q.N = std::span<const double>(stencil.N.data(), n);
    q.G = std::span<const Vec<2>>(stencil.dN.data(), n);
    q.mass = 2.5, q.volume0 = 0.0025, q.inertia_coefficient = 400.0;
    q.F_old << 1.1, 0.2, -0.05, 0.95;
    q.known_minus_b = Vec<2>(0.3, -9.81);
    return q;
  }
};

TEST(MeshfreeResidual, JacobianMatchesCentralDifferences) {
  const Patch patch;
  const auto q = patch.data();
  const NeoHookean material{1000.0, 3e6, 2e6};
  const std::size_t m = q.N.size() * 2;
  ASSERT_GT(m, 12u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  std::vector<double> du(m), r(m), K(m * m), rp(m), rm(m);
  for (auto& d : du) d = u(rng);
  implicit::meshfree_point_residual<2>(q, material, du.data(), r.data(), K.data());
  double scale = 0.0;
  for (double k : K) scale = std::max(scale, std::abs(k));
  const double eps = 1e-7;
  for (std::size_t j = 0; j < m; ++j) {
    auto plus = du, minus = du;
    plus[j] += eps, minus[j] -= eps;
    implicit::meshfree_point_residual<2>(q, material, plus.data(), rp.data(), nullptr);
    implicit::meshfree_point_residual<2>(q, material, minus.data(), rm.data(), nullptr);
    for (std::size_t i = 0; i < m; ++i)
      EXPECT_NEAR(K[i * m + j], (rp[i] - rm[i]) / (2 * eps), 1e-6 * scale) << i << ", " << j;
  }
}

// A rigid translation du_I = c leaves H = 1 (sum grad N_I = 0), so with F^n = 1 the stress term
// vanishes and only the inertia m (c_u c + known - b) N_I remains.
TEST(MeshfreeResidual, RigidTranslationCarriesNoStress) {
  const Patch patch;
  auto q = patch.data();
  q.F_old.setIdentity();
  const NeoHookean material{1000.0, 3e6, 2e6};
  const std::size_t n = q.N.size();
  std::vector<double> du(2 * n), r(2 * n);
  for (std::size_t I = 0; I < n; ++I) du[2 * I] = 0.004, du[2 * I + 1] = -0.002;
  implicit::meshfree_point_residual<2>(q, material, du.data(), r.data(), nullptr);
  const Vec<2> inertia = q.mass * (q.inertia_coefficient * Vec<2>(0.004, -0.002) + q.known_minus_b);
  for (std::size_t I = 0; I < n; ++I)
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(r[2 * I + i], inertia[i] * q.N[I], 1e-9 * inertia.norm()) << I;
}

/// 5 x 5 nodes of spacing h = 0.1 at rest with the consistent a(0) = g of a free fall, no points.
implicit::MeshfreeBody<2> falling_nodes(double h) {
  implicit::MeshfreeBody<2> body;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) body.node_x.emplace_back(i * h, j * h);
  body.fixed.assign(body.node_x.size() * 2, 0);
  body.node_v.assign(body.node_x.size(), Vec<2>::Zero());
  body.node_a.assign(body.node_x.size(), Vec<2>(0.0, -9.81));
  return body;
}

// Free fall from rest: every node's Newmark (beta = 1/4, gamma = 1/2) solution is u = g t^2 / 2,
// v = g t, exactly, for both bases (partition of unity makes a_I = g solve the consistent-mass
// system; the stress stays zero), given the consistent initial acceleration a(0) = g.
TEST(MeshfreeStep, FreeFallIsExact) {
  for (auto basis : {MeshfreeBasis::Mls, MeshfreeBasis::Lme}) {
    const double h = 0.1;
    implicit::MeshfreeBody<2> body = falling_nodes(h);
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        body.point_x.emplace_back((i + 0.5) * h / 2, (j + 0.5) * h / 2);
        body.point_mass.push_back(2.5), body.point_volume0.push_back(0.0025);
        body.point_F.push_back(Mat<2>::Identity());
      }
    implicit::MeshfreeStepOptions options;
    options.shape.basis = basis;
    options.shape.spacing = h;
    options.multipliers = false;
    implicit::MeshfreeStepper<2, NeoHookean> stepper(NeoHookean{1000.0, 3e6, 2e6}, options);
    const auto x0 = body.node_x;
    const auto p0 = body.point_x;
    const Vec<2> g(0.0, -9.81);
    const double dt = 0.01;
    for (int s = 0; s < 10; ++s) ASSERT_TRUE(stepper.step(body, dt, g).converged()) << s;
    const Vec<2> expected = 0.5 * g * 0.01;  // t = 0.1 s
    for (std::size_t I = 0; I < x0.size(); ++I) {
      EXPECT_LT((body.node_x[I] - x0[I] - expected).norm(), 1e-12) << I;
      EXPECT_LT((body.node_v[I] - g * 0.1).norm(), 1e-10) << I;
    }
    for (std::size_t p = 0; p < p0.size(); ++p)
      EXPECT_LT((body.point_x[p] - p0[p] - expected).norm(), 1e-12) << p;
  }
}

// The nodes' history projected from the points (MeshfreeStepper::project_history): both bases
// reproduce linear fields, so points whose v and a are linear in x give nodes whose values are
// that field at the nodes, to round-off, whatever the nodes held before.
TEST(MeshfreeStep, HistoryProjectionReproducesLinearFields) {
  for (auto basis : {MeshfreeBasis::Mls, MeshfreeBasis::Lme}) {
    const double h = 0.1;
    implicit::MeshfreeBody<2> body = falling_nodes(h);
    Mat<2> A, B;
    A << 0.3, -1.2, 0.7, 0.1;
    B << -2.0, 0.5, 1.5, 4.0;
    const Vec<2> c(0.4, -0.2), d(-9.81, 1.0);
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const Vec<2> x((i + 0.5) * h / 2, (j + 0.5) * h / 2);
        body.point_x.push_back(x);
        body.point_mass.push_back(2.5 + 0.1 * i), body.point_volume0.push_back(0.0025);
        body.point_F.push_back(Mat<2>::Identity());
        body.point_v.push_back(A * x + c), body.point_a.push_back(B * x + d);
      }
    for (auto& v : body.node_v) v = Vec<2>(1e3, -1e3);  // anything: the projection replaces it
    implicit::MeshfreeStepOptions options;
    options.shape.basis = basis;
    options.shape.spacing = h;
    options.multipliers = false;
    implicit::MeshfreeStepper<2, NeoHookean> stepper(NeoHookean{1000.0, 3e6, 2e6}, options);
    ASSERT_TRUE(stepper.project_point_history(body));
    for (std::size_t I = 0; I < body.node_x.size(); ++I) {
      EXPECT_LT((body.node_v[I] - (A * body.node_x[I] + c)).norm(), 1e-10) << I;
      EXPECT_LT((body.node_a[I] - (B * body.node_x[I] + d)).norm(), 1e-10) << I;
    }
  }
}

// The deletion repair (the authors' code, extraction §6.5): an LME point outside its nodes' convex
// hull has no shape functions (eq. (61) needs x in conv X), so the step fails; the stepper flags
// exactly that point, and once it is removed the others fall freely, exactly (as above).
TEST(MeshfreeStep, DeletionRemovesOnlyThePointWithoutFunctions) {
  const double h = 0.1;
  implicit::MeshfreeBody<2> body = falling_nodes(h);
  std::vector<Vec<2>> points;  // the free fall's 8 x 8 points, and one outside [0, 0.4]^2 as point 10
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) points.emplace_back((i + 0.5) * h / 2, (j + 0.5) * h / 2);
  points.insert(points.begin() + 10, Vec<2>(0.55, 0.2));
  for (std::size_t p = 0; p < points.size(); ++p) {
    body.point_x.push_back(points[p]);
    body.point_mass.push_back(2.5 + static_cast<double>(p)), body.point_volume0.push_back(0.0025);
    body.point_F.push_back(Mat<2>::Identity());
  }
  implicit::MeshfreeStepOptions options;
  options.shape.basis = MeshfreeBasis::Lme;
  options.shape.spacing = h;
  options.multipliers = false;
  implicit::MeshfreeStepper<2, NeoHookean> stepper(NeoHookean{1000.0, 3e6, 2e6}, options);
  const Vec<2> g(0.0, -9.81);
  EXPECT_EQ(stepper.step(body, 0.01, g).status, implicit::NewtonStatus::AssemblyFailed);
  std::vector<char> gone;
  EXPECT_EQ(stepper.flag_points_without_functions(body, gone), 1u);
  std::vector<char> expected(points.size(), 0);
  expected[10] = 1;
  ASSERT_EQ(gone, expected);
  body.remove_points(gone);
  ASSERT_EQ(body.point_x.size(), 64u);
  EXPECT_EQ(body.point_x[10], points[11]);  // the others keep their order
  EXPECT_EQ(body.point_mass[9], 2.5 + 9);
  EXPECT_EQ(body.point_mass[10], 2.5 + 11);
  EXPECT_EQ(stepper.flag_points_without_functions(body, gone), 0u);
  const auto x0 = body.point_x;
  for (int s = 0; s < 10; ++s) ASSERT_TRUE(stepper.step(body, 0.01, g).converged()) << s;
  for (std::size_t p = 0; p < x0.size(); ++p)
    EXPECT_LT((body.point_x[p] - x0[p] - 0.5 * g * 0.01).norm(), 1e-12) << p;
}

}  // namespace
}  // namespace matpoint
