// FMPM(k) identities of Nairn 2026 (extraction §2.11, tests T1-T6): every one holds in exact
// arithmetic, so the bounds are round-off (1e-12 relative to the velocity scale, a little looser
// where k = 20 passes accumulate rounding).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "matpoint/explicit/fmpm.hpp"
#include "matpoint/explicit/grid_update.hpp"
#include "matpoint/grid/thermal_conditions.hpp"
#include "matpoint/particles/generators.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

/// Random particles with random velocities in a small grid, their stencils, nodal mass and
/// v+(1) = p / m (no force: p+ = p).
template <int D, class Basis>
struct Problem {
  Grid<D> grid;
  ParticleSet<D> particles;
  TensorStencils<D, Basis> stencils;
  GridFields<D> fields;
  std::vector<Vec<D>> v1;  // m^-1 p+

  explicit Problem(int cells, int count = 60, bool uniform_velocity = false, unsigned seed = 3) {
    std::array<int, D> n{};
    n.fill(cells);
    grid = Grid<D>(Vec<D>::Zero(), Vec<D>::Constant(1.0 / cells), n, 0);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < count; ++k) {
      Vec<D> x, v;
      for (int a = 0; a < D; ++a) {
        x[a] = 0.02 + 0.96 * u(rng);
        v[a] = uniform_velocity ? 0.3 + 0.1 * a : u(rng) - 0.5;
      }
      particles.add(x, v, 0.5 + u(rng), 1e-3, Vec<D>::Constant(0.5 / cells), 0, 0);
    }
    sort_by_cell(grid, particles);
    stencils.evaluate(grid, particles);
    fields.resize(grid.node_count);
    scatter_to_grid<kScatterMass | kScatterMomentum>(grid, stencils, particles, Vec<D>(Vec<D>::Zero()),
                                                     fields);
    v1.resize(grid.node_count);
    lumped_velocity(fields, 0.0, v1);
  }

  std::vector<Vec<D>> fmpm(const FmpmSpec& spec, const VelocityConditions<D>& conditions = {},
                           int* order = nullptr) {
    std::vector<Vec<D>> v = v1;
    FmpmLoop<D> loop(spec);
    const int reached = loop.run(grid, stencils, particles, fields.mass, 0.0, conditions, 0.0, v);
    if (order) *order = reached;
    return v;
  }

  /// Dense S (particles x nodes), with the rows of Vec components kept separate by the caller.
  Eigen::MatrixXd dense_s() const {
    Eigen::MatrixXd s = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(particles.size()), grid.node_count);
    for (std::size_t p = 0; p < particles.size(); ++p)
      stencils.for_each_node(
          grid, p, [&](Index i, double N, const Vec<D>&) { s(static_cast<Eigen::Index>(p), i) += N; });
    return s;
  }
};

double max_difference(const auto& a, const auto& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

FmpmSpec order(int k) {
  FmpmSpec s;
  s.order = k;
  return s;
}

// T1: the incremental recursion (eq. 6) equals the original binomial one (eq. 4), k = 1..20.
template <int D, class Basis>
void expect_eq4_equals_eq6() {
  Problem<D, Basis> problem(5);
  for (int k = 1; k <= 20; ++k) {
    FmpmSpec binomial = order(k);
    binomial.recursion = FmpmRecursion::Binomial;
    const auto a = problem.fmpm(order(k)), b = problem.fmpm(binomial);
    // eq. (4) sums terms as large as C(k, l) |v| with alternating signs: rounding grows like 2^k eps.
    EXPECT_LT(max_difference(a, b), 1e-15 * std::pow(2.0, k) * 10) << "k = " << k;
  }
}
TEST(Fmpm, IncrementalEqualsBinomialRecursion1D) { expect_eq4_equals_eq6<1, LinearBasis>(); }
TEST(Fmpm, IncrementalEqualsBinomialRecursion2D) { expect_eq4_equals_eq6<2, QuadraticBSplineBasis>(); }

// T2: v+(k) = sum_{j<k} A^j m^-1 p+ with A = I - m^-1 S^T M S built as dense matrices; and, the
// full mass matrix being nonsingular here (many particles per node), v+(k) -> m~^-1 p+ as k grows:
// the error is A^k m~^-1 p+, and A is self-adjoint in the m-weighted norm with spectral radius
// rho < 1, so that norm of the error falls monotonically and at least as fast as rho^k.
TEST(Fmpm, EqualsDenseTruncatedSeriesAndConvergesToFullMassInverse) {
  Problem<2, LinearBasis> problem(3, 200);
  const Eigen::MatrixXd s = problem.dense_s();
  const Eigen::Index n = s.cols();
  Eigen::VectorXd masses(static_cast<Eigen::Index>(problem.particles.size()));
  for (std::size_t p = 0; p < problem.particles.size(); ++p)
    masses(static_cast<Eigen::Index>(p)) = problem.particles.mass[p];
  const Eigen::MatrixXd full = s.transpose() * masses.asDiagonal() * s;  // m~ = S^T M S
  const Eigen::VectorXd lumped = full.rowwise().sum();                   // m = diag(S^T M)
  const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) - lumped.cwiseInverse().asDiagonal() * full;
  for (int c = 0; c < 2; ++c) {
    Eigen::VectorXd v1(n), momentum(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      v1(i) = problem.v1[i][c];
      momentum(i) = problem.fields.momentum[i][c];
    }
    const Eigen::VectorXd exact = full.ldlt().solve(momentum);
    // A = I - m^-1/2 (m^-1/2 m~ m^-1/2) m^1/2: its eigenvalues are those of a symmetric matrix.
    const Eigen::VectorXd root = lumped.cwiseSqrt();
    const Eigen::MatrixXd symmetric =
        root.cwiseInverse().asDiagonal() * full * root.cwiseInverse().asDiagonal();
    const Eigen::VectorXd eigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(symmetric).eigenvalues();
    const double rho = std::max(std::abs(1.0 - eigen.minCoeff()), std::abs(1.0 - eigen.maxCoeff()));
    ASSERT_LT(rho, 1.0) << "nonsingular full mass matrix";
    auto m_norm = [&](const Eigen::VectorXd& x) { return root.cwiseProduct(x).norm(); };
    const double error0 = m_norm(exact);
    Eigen::VectorXd series = Eigen::VectorXd::Zero(n), term = v1;
    double previous_error = error0;
    for (int k = 1; k <= 40; ++k) {
      series += term;
      term = a * term;
      const auto v = problem.fmpm(order(k));
      for (Eigen::Index i = 0; i < n; ++i)
        EXPECT_NEAR(v[i][c], series(i), 1e-12) << "k = " << k << ", node " << i;
      const double error = m_norm(series - exact);
      EXPECT_LE(error, previous_error * (1 + 1e-12)) << "the error falls monotonically, k = " << k;
      EXPECT_LE(error, std::pow(rho, k) * error0 * (1 + 1e-9) + 1e-13) << "k = " << k;
      previous_error = error;
    }
  }
}

// T3: a uniform particle velocity gives dv(2) = 0: FMPM(k) leaves it unchanged and dynamic FMPM
// stops at l = 2 (Nairn 2026 §3.4).
TEST(Fmpm, UniformVelocityIsAFixedPointAndDynamicLoopStopsAtOrderTwo) {
  Problem<2, QuadraticBSplineBasis> problem(4, 150, /*uniform_velocity=*/true);
  const auto v = problem.fmpm(order(10));
  EXPECT_LT(max_difference(v, problem.v1), 1e-13);
  FmpmSpec dynamic = order(20);
  dynamic.measure = FmpmMeasure::Means;
  dynamic.limit = 1e-10;
  int reached = 0;
  problem.fmpm(dynamic, {}, &reached);
  EXPECT_EQ(reached, 2);
}

// T4: without conditions every increment carries zero momentum, so sum_i m_i v+(k)_i = sum_i p+_i.
TEST(Fmpm, ConservesLinearMomentumWithoutConditions) {
  Problem<3, QuadraticBSplineBasis> problem(3, 100);
  Vec<3> p_plus = Vec<3>::Zero();
  for (Index i = 0; i < problem.grid.node_count; ++i) p_plus += problem.fields.momentum[i];
  for (int k : {2, 5, 20}) {
    const auto v = problem.fmpm(order(k));
    Vec<3> p = Vec<3>::Zero();
    for (Index i = 0; i < problem.grid.node_count; ++i) p += problem.fields.mass[i] * v[i];
    EXPECT_LT((p - p_plus).norm(), 1e-13 * problem.particles.size()) << "k = " << k;
  }
}

/// Superposed conditions: a fixed x- face, a slip y- face and a moving box that overlaps both
/// (it starts left of the domain, so the x- face nodes below y = 0.3 carry the fixed condition and
/// the box's v_x = 0.25, which superpose to v = (0.25, 0); Nairn 2026 Table 2).
VelocityConditions<2> superposed_conditions(const Grid<2>& grid) {
  std::vector<VelocityConditionSpec> specs(3);
  specs[0].on_face = true;  // x- fixed
  specs[0].face_axis = 0;
  specs[0].kind = ConditionKind::Fixed;
  specs[1].on_face = true;  // y- slip (v_y = 0)
  specs[1].face_axis = 1;
  specs[1].kind = ConditionKind::Slip;
  specs[1].normal_axis = 1;
  specs[2].on_face = false;  // a box of nodes moving at v_x = 0.25 (parallel to the slip face)
  specs[2].box_min = {-1.0, -1.0, 0.0};
  specs[2].box_max = {1.0, 0.3, 0.0};
  specs[2].kind = ConditionKind::Velocity;
  specs[2].velocity[0] = TimeFunction{{}, {0.25}};
  return {specs, grid};
}

// T5: after the loop the conditions hold exactly on their nodes, for every k (eq. 12).
TEST(Fmpm, ConditionsHoldExactlyAfterTheLoop) {
  Problem<2, QuadraticBSplineBasis> problem(5, 120);
  const auto conditions = superposed_conditions(problem.grid);
  conditions.apply(problem.v1, 0.0);  // v+(1) with the lumped conditions (Table 2, top block)
  for (int k = 1; k <= 12; ++k) {
    const auto v = problem.fmpm(order(k), conditions);
    for (Index i = 0; i < problem.grid.node_count; ++i) {
      const Vec<2> x = problem.grid.node_position(i);
      const bool in_box = x[1] < 0.3 + 1e-9;
      if (x[0] < 1e-12) {
        EXPECT_EQ(v[i][1], 0.0) << "fixed node " << i << ", k = " << k;
        EXPECT_EQ(v[i][0], in_box ? 0.25 : 0.0) << "fixed node " << i << ", k = " << k;
      }
      if (x[1] < 1e-12) {
        EXPECT_EQ(v[i][1], 0.0) << "slip node " << i << ", k = " << k;
      }
      if (in_box) {
        EXPECT_EQ(v[i][0], 0.25) << "moving node " << i << ", k = " << k;
      }
    }
  }
}

// T6: the new boundary method equals the old "combined" one for k <= 2 and differs for k = 3.
TEST(Fmpm, IncrementalConditionsEqualCombinedUpToOrderTwoOnly) {
  Problem<2, LinearBasis> problem(5, 120);
  const auto conditions = superposed_conditions(problem.grid);
  conditions.apply(problem.v1, 0.0);
  for (int k = 1; k <= 3; ++k) {
    FmpmSpec combined = order(k);
    combined.boundary_method = FmpmBoundaryMethod::Combined;
    const double difference =
        max_difference(problem.fmpm(order(k), conditions), problem.fmpm(combined, conditions));
    if (k <= 2)
      EXPECT_LT(difference, 1e-14) << "k = " << k;
    else
      EXPECT_GT(difference, 1e-4) << "k = " << k;
  }
}

// Blending with FMPM(2) (Nairn 2026 §3.3): the series I + A + a A^2 + a A^3 + a^2 A^4 + ...;
// blending with FMPM(1): I + a A + a^2 A^2 + ...; with a = 1 both are plain FMPM(k).
TEST(Fmpm, BlendingReproducesItsSeries) {
  Problem<1, LinearBasis> problem(6, 40);
  const double alpha = 0.7;
  const int k = 6;
  for (int with : {1, 2}) {
    std::vector<std::vector<Vec<1>>> powers{problem.v1};  // A^j v1 from single unblended passes
    for (int j = 1; j < k; ++j) {
      std::vector<Vec<1>> next;
      FmpmLoop<1> loop(order(2));
      loop.apply_projection(problem.grid, problem.stencils, problem.particles, problem.fields.mass, 0.0,
                            powers.back(), next);
      for (std::size_t i = 0; i < next.size(); ++i) next[i] = powers.back()[i] - next[i];
      powers.push_back(next);
    }
    std::vector<Vec<1>> expected(problem.v1.size(), Vec<1>::Zero());
    for (int j = 0; j < k; ++j) {
      const int scaled = with == 1 ? j : j / 2;  // number of alpha factors in front of A^j
      for (std::size_t i = 0; i < expected.size(); ++i) expected[i] += std::pow(alpha, scaled) * powers[j][i];
    }
    FmpmSpec blended = order(k);
    blended.blend_with = with;
    blended.blend_factor = alpha;
    EXPECT_LT(max_difference(problem.fmpm(blended), expected), 1e-13) << "blend with FMPM(" << with << ")";
    blended.blend_factor = 1.0;
    EXPECT_LT(max_difference(problem.fmpm(blended), problem.fmpm(order(k))), 1e-15);
  }
}

}  // namespace

namespace {

// Transport FMPM (Nairn 2026 §3.5): the same loop instantiated for scalars, with particle weights
// w_p in place of M_p and the capacity sum_p w_p S_pi in place of the mass. With w_p = M_p it must
// give, component by component, the velocities of the mechanics loop (the same arithmetic).
TEST(FmpmTransport, ScalarLoopWithMassWeightsReproducesEachVelocityComponent) {
  Problem<2, QuadraticBSplineBasis> problem(4);
  const auto velocity = problem.fmpm(order(5));
  for (int a = 0; a < 2; ++a) {
    std::vector<double> T(problem.v1.size());
    for (std::size_t i = 0; i < T.size(); ++i) T[i] = problem.v1[i][a];
    FmpmLoop<2, double> loop(order(5));
    loop.set_particle_weights(&problem.particles.mass);
    loop.run(problem.grid, problem.stencils, problem.particles, problem.fields.mass, 0.0,
             ThermalConditions<2>{}, 0.0, T);
    for (std::size_t i = 0; i < T.size(); ++i) EXPECT_NEAR(T[i], velocity[i][a], 1e-13) << "node " << i;
  }
}

}  // namespace
