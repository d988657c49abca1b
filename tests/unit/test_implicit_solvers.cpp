// Generic implicit machinery: sparse assembly, linear solvers, Newton (implicit/), and the
// assembled particle-Newmark system on a small patch.
//   - Assembly: two overlapping blocks against the sum written by hand; Dirichlet rows identity;
//     the same values with 1 and 2 threads (coloured, deterministic assembly).
//   - Linear solvers: every back-end solves one nonsymmetric system (upwind convection-diffusion)
//     whose exact solution x* is chosen, to |x - x*| / |x*| < 1e-10 (the brief; the extraction's
//     A16 asks 1e-10 of the Krylov solvers).
//   - The assembled Jacobian of the patch equals central differences of the assembled residual
//     (extraction AT-3, for the whole system with inactive-node equations and Dirichlet rows).
//   - AT-4: Newton's method converges quadratically on a deformed patch: with a Lipschitz
//     Jacobian, e_{k+1} <= M e_k^2 near the root (Kantorovich; e.g. Kelley, Iterative Methods for
//     Linear and Nonlinear Equations, Thm. 5.1.1), so the ratios e_{k+1} / e_k^2 stay bounded,
//     while under linear convergence they would grow like 1 / e_k.
//   - Round-off stop: a linear system whose residual is formed by cancellation (K (U + u) - f with
//     |U| ~ 5e9 |u*|, as an updated-Lagrangian internal force carries the whole history) has a
//     residual floor near eps |K| |U| (measured: 3e-7 |R_0|, constant from the first iterate on)
//     and an increment noise near eps |U| (5e-7 |u*|), so the 1e-9 increment test is never met:
//     Newton must stop at the floor as converged.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "linear_test_systems.hpp"
#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/newton.hpp"
#include "matpoint/implicit/particle_newmark/element_flags.hpp"
#include "matpoint/implicit/particle_newmark/particle_newmark_system.hpp"
#include "matpoint/material/neo_hookean.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;
using mesh::Q9;

TEST(ImplicitAssembly, OverlappingBlocksSumAndDirichletRowsAreIdentity) {
  SparseAssembly a;
  const std::vector<Index> offsets{0, 2, 4}, dofs{0, 1, 1, 2};
  const std::vector<char> dirichlet{0, 0, 1};
  a.build(3, offsets, dofs, dirichlet);
  Eigen::VectorXd R;
  SparseMatrix K;
  a.assemble(
      [](Index b, std::span<const Index>, double* r, double* k) {
        const double s = b == 0 ? 1.0 : 10.0;
        r[0] = s, r[1] = 2 * s;
        k[0] = s, k[1] = 2 * s, k[2] = 3 * s, k[3] = 4 * s;  // row-major [[s, 2s], [3s, 4s]]
      },
      R, &K);
  const Eigen::MatrixXd dense(K);
  Eigen::MatrixXd expected(3, 3);
  expected << 1, 2, 0,  //
      3, 4 + 10, 20,    //
      0, 0, 1;          // dof 2: Dirichlet row
  EXPECT_EQ(dense, expected);
  EXPECT_EQ(R, Eigen::Vector3d(1, 2 + 10, 0));
  EXPECT_EQ(a.colour_count(), 2);
}

// build() with the blocks and Dirichlet flags of the present pattern keeps it and its version (the
// linear solver then keeps its symbolic analysis: a meshfree body whose clouds did not change, an
// active set that stayed); any change, in the blocks or the flags, makes a new version.
TEST(ImplicitAssembly, TheSameBlocksKeepThePatternVersion) {
  SparseAssembly a;
  const std::vector<Index> offsets{0, 2, 4}, dofs{0, 1, 1, 2}, other_dofs{0, 1, 0, 2};
  const std::vector<char> dirichlet{0, 0, 1}, no_dirichlet;
  a.build(3, offsets, dofs, dirichlet);
  const std::uint64_t first = a.pattern_version();
  a.build(3, offsets, dofs, dirichlet);
  EXPECT_EQ(a.pattern_version(), first);
  a.build(3, offsets, other_dofs, dirichlet);
  const std::uint64_t second = a.pattern_version();
  EXPECT_NE(second, first);
  const SparseMatrix& P = a.pattern();  // column 2 now couples dofs 0 and 2, no longer 1
  const std::vector<int> rows_of_column_2(P.innerIndexPtr() + P.outerIndexPtr()[2],
                                          P.innerIndexPtr() + P.outerIndexPtr()[3]);
  EXPECT_EQ(rows_of_column_2, (std::vector<int>{0, 2}));
  a.build(3, offsets, other_dofs, no_dirichlet);
  EXPECT_NE(a.pattern_version(), second);
}

using test::convection_diffusion;

TEST(ImplicitLinearSolver, EveryBackEndSolvesANonsymmetricSystem) {
  const SparseMatrix A = convection_diffusion(20);
  Eigen::VectorXd x_exact(A.rows());
  for (Eigen::Index i = 0; i < x_exact.size(); ++i)
    x_exact[i] = std::sin(0.37 * static_cast<double>(i)) + 0.5;
  const Eigen::VectorXd b = A * x_exact;
  for (const auto kind : {LinearSolverKind::Umfpack, LinearSolverKind::Klu, LinearSolverKind::BicgstabIlut,
                          LinearSolverKind::GmresIlut}) {
    LinearSolverOptions options;
    options.kind = kind;
    options.relative_tolerance = 1e-13;
    const auto solver = make_linear_solver(options);
    Eigen::VectorXd x;
    ASSERT_TRUE(solver->factorize(A, 7)) << solver->name() << ": " << solver->message();
    ASSERT_TRUE(solver->solve(b, x)) << solver->name() << ": " << solver->message();
    EXPECT_LT((x - x_exact).norm(), 1e-10 * x_exact.norm()) << solver->name();
    // Same pattern, new values: no second symbolic analysis.
    const SparseMatrix A2 = 2.0 * A;
    ASSERT_TRUE(solver->factorize(A2, 7));
    ASSERT_TRUE(solver->solve(b, x));
    EXPECT_LT((x - 0.5 * x_exact).norm(), 1e-10 * x_exact.norm()) << solver->name();
    EXPECT_EQ(solver->stats().analyses, 1) << solver->name();
    EXPECT_EQ(solver->stats().factorizations, 2) << solver->name();
  }
}

TEST(ImplicitLinearSolver, SingularMatrixIsAFailureNotAnException) {
  SparseMatrix A(2, 2);
  A.insert(0, 0) = 1.0;
  A.insert(1, 0) = 1.0;
  A.makeCompressed();
  const auto solver = make_linear_solver();
  Eigen::VectorXd x;
  const bool ok = solver->factorize(A, 1) && solver->solve(Eigen::Vector2d(1, 2), x);
  EXPECT_FALSE(ok);
  EXPECT_FALSE(solver->message().empty());
}

/// A 3 x 2 Q9 mesh of unit cells; particles at the 3 x 3 Gauss points of the bottom-left 2 x 2
/// elements... the left 2 x 2 block (elements 0, 1, 3, 4); the right column stays inactive. The
/// bottom side is clamped. Body force b, F^n = I, the inertia of a long step (dt = 1).
struct Patch {
  mesh::Mesh<2> mesh;
  ActiveSet set;
  ParticleQuadrature<Q9> q;
  std::vector<NeoHookean> materials{NeoHookean{1000.0, 1.5e6, 1.0e6}};
  std::vector<char> dirichlet;
  ParticleNewmarkSystem<Q9, NeoHookean> system;

  explicit Patch(double body_force, bool receding) {
    mesh = mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 3, 3),
                                      mesh::AxisSpacing::uniform(0, 2, 2));
    const auto& rule = mesh::gauss_rule<Q9>(3);
    const std::vector<Index> hosts_of_blocks{0, 1, 3, 4};
    std::vector<Index> host;
    for (const Index e : hosts_of_blocks)
      for (std::size_t g = 0; g < rule.points.size(); ++g) host.push_back(e);
    set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
    const NewmarkCoefficients c(NewmarkParameters{}, 1.0);
    for (const Index e : set.active_elements) {
      const auto X = gather_nodes<Q9>(mesh.nodes, mesh.element_nodes(e));
      for (std::size_t g = 0; g < rule.points.size(); ++g) {
        const double w = rule.weights[g] * (X.transpose() * Q9::gradients(rule.points[g])).determinant();
        // Old velocity upwards: moving away from the clamped bottom (receding switch of A4).
        const Vec<2> v_old(0.0, 0.1), b(0.5 * body_force, -body_force);
        const auto bits = receding ? receding_switches<Q9>(X, {0.5, 0.0, 0.0, 0.0}, v_old) : 0u;
        q.add(0, rule.points[g], X, 0, 1000.0 * w, w, 0, Mat<2>::Identity(),
              c.known<2>(v_old, Vec<2>::Zero()) - b, bits);
      }
      q.close_block();
    }
    dirichlet.assign(static_cast<std::size_t>(mesh.node_count() * 2), 0);
    for (const Index node : mesh.node_sets.at("bottom"))
      dirichlet[static_cast<std::size_t>(2 * node)] = dirichlet[static_cast<std::size_t>(2 * node + 1)] = 1;
    const auto flags = element_flags(set, 9, mesh.connectivity, FlagRule::Paper);
    const auto ce =
        soft_stiffness_factors(flags, SoftStiffnessTable{{{5, 1e-2}, {9, 1e-4}}}, FlagRule::Paper);
    typename ParticleNewmarkSystem<Q9, NeoHookean>::StepData data;
    data.mesh = &mesh;
    data.reference_nodes = mesh.nodes;
    data.set = &set;
    data.quadrature = &q;
    data.materials = materials;
    for (const double x : ce) data.soft_stiffness.push_back(materials[0].mu * x);
    if (receding)
      for (const Index e : set.active_elements) data.receding.push_back({e < 3 ? 0.5 : 0.0, 0.0, 0.0, 0.0});
    data.dirichlet = dirichlet;
    data.options.inertia_coefficient = c.displacement;
    system.setup(std::move(data));
  }
};

TEST(ImplicitSystem, AssembledJacobianMatchesCentralDifferences) {
  const Patch patch(200.0, true);
  const Index n = patch.system.dof_count();
  Eigen::VectorXd u(n);
  for (Index i = 0; i < n; ++i)
    u[i] = patch.dirichlet[static_cast<std::size_t>(i)] ? 0.0 : 0.01 * std::sin(0.9 * i);
  Eigen::VectorXd R, Rp, Rm;
  SparseMatrix K;
  ASSERT_TRUE(patch.system.assemble(u, R, &K));
  const Eigen::MatrixXd Kd(K);
  const double h = 1e-6;
  double max_error = 0.0;
  for (Index j = 0; j < n; ++j) {
    if (patch.dirichlet[static_cast<std::size_t>(j)]) continue;  // columns of fixed dofs never move
    Eigen::VectorXd up = u, um = u;
    up[j] += h, um[j] -= h;
    patch.system.assemble(up, Rp, nullptr);
    patch.system.assemble(um, Rm, nullptr);
    max_error = std::max(max_error, ((Rp - Rm) / (2 * h) - Kd.col(j)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(max_error, 1e-6 * Kd.cwiseAbs().maxCoeff());
  // Inactive-only nodes (the right column's interior and far side) have the diagonal mass rows.
  EXPECT_GT(patch.set.inactive_elements.size(), 0u);
}

TEST(ImplicitLinearSolver, EveryBackEndSolvesTheAssembledPatchJacobian) {
  // The implicit MPM matrix itself (nonsymmetric with the receding correction, Dirichlet identity
  // rows, diagonal inactive-node rows), with a chosen solution x*: b = K x*.
  const Patch patch(100.0, true);
  const Index n = patch.system.dof_count();
  Eigen::VectorXd u = Eigen::VectorXd::Constant(n, 0.0), R, x;
  SparseMatrix K;
  ASSERT_TRUE(patch.system.assemble(u, R, &K));
  Eigen::VectorXd x_exact(n);
  for (Index i = 0; i < n; ++i) x_exact[i] = std::cos(0.3 * static_cast<double>(i));
  const Eigen::VectorXd b = K * x_exact;
  for (const auto kind : {LinearSolverKind::Umfpack, LinearSolverKind::Klu, LinearSolverKind::BicgstabIlut,
                          LinearSolverKind::GmresIlut}) {
    LinearSolverOptions options;
    options.kind = kind;
    options.relative_tolerance = 1e-14;
    const auto solver = make_linear_solver(options);
    ASSERT_TRUE(solver->factorize(K, patch.system.assembly().pattern_version()) && solver->solve(b, x))
        << solver->name() << ": " << solver->message();
    EXPECT_LT((x - x_exact).norm(), 1e-10 * x_exact.norm()) << solver->name();
  }
}

TEST(ImplicitSystem, TaylorRemainderOfTheAssembledResidualIsSecondOrder) {
  // R(u + t d) - R(u) - t K d = O(t^2) exactly when K = dR/du (Taylor): halving t divides the
  // remainder by 4; an inexact K would leave a first-order part that halves only by 2.
  const Patch patch(100.0, true);
  const Index n = patch.system.dof_count();
  Eigen::VectorXd u(n), d(n), R0, Rt;
  for (Index i = 0; i < n; ++i) {
    const bool fixed = patch.dirichlet[static_cast<std::size_t>(i)] != 0;
    u[i] = fixed ? 0.0 : 0.05 * std::sin(0.9 * i);
    d[i] = fixed ? 0.0 : std::cos(1.3 * i);
  }
  SparseMatrix K;
  ASSERT_TRUE(patch.system.assemble(u, R0, &K));
  const Eigen::VectorXd Kd = K * d;
  std::vector<double> remainder;
  for (double t = 1e-3; t > 1e-5; t *= 0.5) {
    patch.system.assemble(u + t * d, Rt, nullptr);
    remainder.push_back((Rt - R0 - t * Kd).norm());
  }
  for (std::size_t k = 1; k < remainder.size(); ++k) {
    std::cout << "remainder ratio " << remainder[k - 1] / remainder[k] << "\n";
    EXPECT_NEAR(remainder[k - 1] / remainder[k], 4.0, 0.2) << k;
  }
}

TEST(ImplicitSystem, AssemblyIsTheSameWithOneAndTwoThreads) {
  const Patch patch(200.0, true);
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(patch.system.dof_count(), -0.01, 0.01), R1, R2;
  SparseMatrix K1, K2;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  patch.system.assemble(u, R1, &K1);
  omp_set_num_threads(2);
  patch.system.assemble(u, R2, &K2);
  omp_set_num_threads(threads);
  EXPECT_EQ(R1, R2);
  EXPECT_EQ(Eigen::MatrixXd(K1), Eigen::MatrixXd(K2));
}

TEST(ImplicitNewton, ConvergesQuadraticallyOnADeformedPatch) {
  const Patch patch(100.0, true);
  auto solver = make_linear_solver();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(patch.system.dof_count());
  NewtonOptions options;
  options.components = 2;
  const NewtonResult result = newton_solve([&](const Eigen::VectorXd& x, Eigen::VectorXd& R,
                                               SparseMatrix* K) { return patch.system.assemble(x, R, K); },
                                           patch.system.assembly().pattern_version(), *solver, u, options);
  ASSERT_TRUE(result.converged()) << result.message;
  const auto& h = result.history;
  std::cout << "k  |R_k|  |du_k|  |R_k+1|/|R_k|^2  |du_k+1|/|du_k|^2\n";
  for (std::size_t k = 0; k < h.size(); ++k) {
    const bool next = k + 1 < h.size();
    std::cout << k << "  " << h[k].residual_norm << "  " << h[k].increment_norm << "  "
              << (next ? h[k + 1].residual_norm / (h[k].residual_norm * h[k].residual_norm) : 0.0) << "  "
              << (next ? h[k + 1].increment_norm / (h[k].increment_norm * h[k].increment_norm) : 0.0) << "\n";
  }
  // A deformed state: the largest displacement is a good fraction of the 1 m cells.
  const double u_max = u.cwiseAbs().maxCoeff();
  EXPECT_GT(u_max, 0.05);
  // Quadratic phase, on the increments (|du_k| ~ the error of u_k): the ratios
  // M_k = |du_{k+1}| / |du_k|^2 stay bounded (within a factor 100 of the previous one) once
  // |du_k| < 1e-2 |u| and while |du_{k+1}| is above round-off (1e-12 |u|). Under linear
  // convergence |du_{k+1}| = rho |du_k| they would grow by 1 / rho per iteration, and every such
  // iteration must also cut the error by more than that factor (checked: contraction < 1e-2).
  const double un = u.norm();
  int checked = 0;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {
    if (h[k + 1].increment_norm < 1e-12 * un || h[k].increment_norm > 1e-2 * un) continue;
    const double ratio = h[k + 1].increment_norm / (h[k].increment_norm * h[k].increment_norm);
    const double previous = h[k].increment_norm / (h[k - 1].increment_norm * h[k - 1].increment_norm);
    EXPECT_LT(ratio, 100.0 * previous) << "iteration " << k;
    EXPECT_LT(h[k + 1].increment_norm, 1e-2 * h[k].increment_norm) << "iteration " << k;
    ++checked;
  }
  EXPECT_GE(checked, 1);
  EXPECT_LE(result.iterations(), 8);
  // The converged state solves the system: |R| down by 10 orders from the start.
  EXPECT_LT(result.final_residual_norm, 1e-10 * h[0].residual_norm);
}

TEST(ImplicitNewton, LineSearchMakesTheResidualDecreaseAndTheResidualTestStopsEarly) {
  // Under a load where full Newton steps first raise |R| (see the quadratic test's history at 300),
  // the backtracking search accepts only steps with |R(u + s du)| <= (1 - 1e-4 s) |R(u)| (Armijo),
  // so the recorded residuals decrease monotonically, and it still converges.
  const Patch patch(300.0, true);
  auto solver = make_linear_solver();
  const auto assemble = [&](const Eigen::VectorXd& x, Eigen::VectorXd& R, SparseMatrix* K) {
    return patch.system.assemble(x, R, K);
  };
  NewtonOptions options;
  options.components = 2;
  options.line_search = true;
  options.max_iterations = 30;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(patch.system.dof_count());
  const NewtonResult searched =
      newton_solve(assemble, patch.system.assembly().pattern_version(), *solver, u, options);
  ASSERT_TRUE(searched.converged()) << searched.message;
  for (std::size_t k = 1; k < searched.history.size(); ++k) {
    if (searched.history[k - 1].residual_norm < 1e-6 * searched.history[0].residual_norm) break;  // round-off
    EXPECT_LT(searched.history[k].residual_norm, searched.history[k - 1].residual_norm) << "iteration " << k;
  }
  EXPECT_LT(searched.history[1].step_length, 1.0);  // the first full step was cut
  // Residual test: |R| <= 1e-3 |R_0| ends the iterations before the increment test would.
  options.line_search = false;
  options.residual_relative = 1e-3;
  u.setZero();
  const NewtonResult early =
      newton_solve(assemble, patch.system.assembly().pattern_version(), *solver, u, options);
  ASSERT_TRUE(early.converged());
  EXPECT_LE(early.final_residual_norm, 1e-3 * early.history[0].residual_norm);
  EXPECT_GT(early.final_residual_norm, 1e-10 * early.history[0].residual_norm);
}

TEST(ImplicitNewton, StopsAtTheRoundOffFloorOfACancellingResidual) {
  SparseAssembly pattern;
  const std::vector<Index> offsets{0, 2}, dofs{0, 1};
  pattern.build(2, offsets, dofs, {});
  Eigen::Matrix2d k_dense;
  k_dense << 2.1e3 / 3.0, -1e3 / 7.0, -1.1e3 / 7.0, 1.9e3 / 3.0;  // entries not exact in binary
  const Eigen::Vector2d history_offset(std::sqrt(2.0) * 1e6, std::sqrt(3.0) * 1e6),
      root(1e-3 / 3.0, -2e-3 / 7.0);
  // f rounded apart from K (U + u*), so no double u makes the computed residual exactly 0.
  const Eigen::Vector2d f = k_dense * history_offset + k_dense * root;
  const auto assemble = [&](const Eigen::VectorXd& x, Eigen::VectorXd& R, SparseMatrix* K) {
    R = k_dense * (history_offset + x) - f;
    if (K) {
      *K = pattern.pattern();
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) K->coeffRef(i, j) = k_dense(i, j);
    }
    return true;
  };
  auto solver = make_linear_solver();
  NewtonOptions options;
  options.round_off_relative = 0.0;  // without the stop: the increment test is never met
  Eigen::VectorXd u = Eigen::VectorXd::Zero(2);
  const NewtonResult wandering = newton_solve(assemble, pattern.pattern_version(), *solver, u, options);
  EXPECT_EQ(wandering.status, NewtonStatus::MaxIterations);
  options.round_off_relative = 1e-6;
  u.setZero();
  const NewtonResult stopped = newton_solve(assemble, pattern.pattern_version(), *solver, u, options);
  ASSERT_TRUE(stopped.converged()) << stopped.message;
  EXPECT_TRUE(stopped.round_off_stop);
  EXPECT_LE(stopped.iterations(), 4);
  // The answer is the root to the floor: |u - u*| <= 1e-5 |u*| (the floor is ~3e-7 |u*|).
  EXPECT_LT((u - Eigen::VectorXd(root)).norm(), 1e-5 * root.norm());
  EXPECT_LE(stopped.final_residual_norm, 1e-6 * stopped.history[0].residual_norm);
}

TEST(ImplicitNewton, NumericalTroubleIsAStatusNotAnException) {
  auto solver = make_linear_solver();
  Eigen::VectorXd u = Eigen::VectorXd::Ones(2);
  SparseAssembly pattern;
  const std::vector<Index> offsets{0, 2}, dofs{0, 1};
  pattern.build(2, offsets, dofs, {});
  // NaN residual.
  auto result = newton_solve(
      [&](const Eigen::VectorXd&, Eigen::VectorXd& R, SparseMatrix* K) {
        R = Eigen::Vector2d(std::nan(""), 0.0);
        if (K) *K = pattern.pattern();
        return true;
      },
      pattern.pattern_version(), *solver, u);
  EXPECT_EQ(result.status, NewtonStatus::NotFinite);
  // Singular Jacobian (all zeros).
  result = newton_solve(
      [&](const Eigen::VectorXd&, Eigen::VectorXd& R, SparseMatrix* K) {
        R = Eigen::Vector2d(1.0, 1.0);
        if (K) *K = pattern.pattern();
        return true;
      },
      pattern.pattern_version(), *solver, u);
  EXPECT_EQ(result.status, NewtonStatus::LinearSolveFailed);
}

}  // namespace
