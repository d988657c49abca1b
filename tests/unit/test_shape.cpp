// Shape functions: partition of unity, linear-field reproduction, zero gradient sum and gradient
// consistency, everywhere in the domain including cells next to its edge.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

template <int D, class Basis>
void check_basis(int cells) {
  Vec<D> origin = Vec<D>::Constant(-0.3), h;
  std::array<int, D> n{};
  for (int a = 0; a < D; ++a) {
    h[a] = 0.1 + 0.05 * a;
    n[a] = cells;
  }
  const Grid<D> grid(origin, h, n, Basis::ghost_layers);
  ParticleSet<D> ps;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    Vec<D> x;
    for (int a = 0; a < D; ++a) {
      double t = u(rng);
      if (k % 4 == 0) t = 0.02 * t;        // first cell
      if (k % 4 == 1) t = 1.0 - 0.02 * t;  // last cell
      x[a] = origin[a] + t * cells * h[a];
    }
    if (k == 0) x = origin;  // exactly on the domain corner
    ps.add(x, Vec<D>::Zero(), 1.0, 1.0, h, 0, 0);
  }
  TensorStencils<D, Basis> st;
  st.evaluate(grid, ps);
  const Vec<D> slope = Vec<D>::LinSpaced(D, 1.5, -2.0);  // f(x) = 0.7 + slope . x
  for (std::size_t p = 0; p < ps.size(); ++p) {
    double sum = 0, f = 0;
    Vec<D> grad_sum = Vec<D>::Zero(), grad_f = Vec<D>::Zero(), moment = Vec<D>::Zero();
    st.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
      ASSERT_GE(node, 0);
      ASSERT_LT(node, grid.node_count);
      const Vec<D> xi = grid.node_position(node);
      sum += N;
      grad_sum += dN;
      moment += N * xi;
      const double fi = 0.7 + slope.dot(xi);
      f += N * fi;
      grad_f += fi * dN;
    });
    EXPECT_NEAR(sum, 1.0, 1e-13) << "partition of unity, particle " << p;
    EXPECT_LT((moment - ps.x[p]).norm(), 1e-13) << "linear reproduction, particle " << p;
    EXPECT_NEAR(f, 0.7 + slope.dot(ps.x[p]), 1e-12);
    EXPECT_LT(grad_sum.norm(), 1e-11) << "gradients sum to zero";
    EXPECT_LT((grad_f - slope).norm(), 1e-11) << "gradient of a linear field";
  }
}

TEST(Shape, FarOutsideOrNonFiniteCoordinatesStayDefined) {
  // A diverging run can put a CPDI corner 1e10 cells away (UBSan, stability scan): the cell index
  // is limited instead of overflowing int, and the folded window stays inside the grid.
  EXPECT_EQ(floor_to_int(-2.5), -3);
  EXPECT_EQ(floor_to_int(7.0), 7);
  EXPECT_EQ(floor_to_int(1e300), 1 << 28);
  EXPECT_EQ(floor_to_int(-1e300), -(1 << 28));
  EXPECT_EQ(floor_to_int(std::nan("")), -(1 << 28));
  for (double xi : {1e10, -1e10}) {
    double w[kMaxKernelWidth], dw[kMaxKernelWidth];
    const int start = point_on_grid<HatKernel>(xi, 10, w, dw);  // a window of nodes 0 .. 10
    EXPECT_GE(start, 0);
    EXPECT_LE(start, 10 - HatKernel::point_width + 1);
    const int q = point_on_grid<QuadraticKernel>(xi, 10, w, dw);
    EXPECT_GE(q, 0);
    EXPECT_LE(q, 10 - QuadraticKernel::point_width + 1);
  }
}

TEST(Shape, LinearIsPartitionOfUnityAndReproducesLinearFields) {
  check_basis<1, LinearBasis>(7);
  check_basis<2, LinearBasis>(7);
  check_basis<3, LinearBasis>(5);
}

TEST(Shape, QuadraticBSplineIsPartitionOfUnityAndReproducesLinearFields) {
  check_basis<1, QuadraticBSplineBasis>(7);
  check_basis<2, QuadraticBSplineBasis>(7);
  check_basis<3, QuadraticBSplineBasis>(5);
}

/// d N / dx equals the central finite difference of N for every node, away from kinks.
template <class Basis>
void check_gradient_is_derivative() {
  const Grid<1> grid(Vec<1>(0.0), Vec<1>(0.25), {8}, Basis::ghost_layers);
  const double eps = 1e-7;
  for (double x : {0.11, 0.37, 0.61, 1.02, 1.33, 1.9}) {
    ParticleSet<1> ps;
    for (double y : {x, x - eps, x + eps}) ps.add(Vec<1>(y), Vec<1>::Zero(), 1, 1, Vec<1>(0.25), 0, 0);
    TensorStencils<1, Basis> st;
    st.evaluate(grid, ps);
    std::map<Index, double> value_minus, value_plus, gradient;
    st.for_each_node(grid, 0, [&](Index n, double, const Vec<1>& dN) { gradient[n] = dN[0]; });
    st.for_each_node(grid, 1, [&](Index n, double N, const Vec<1>&) { value_minus[n] = N; });
    st.for_each_node(grid, 2, [&](Index n, double N, const Vec<1>&) { value_plus[n] = N; });
    for (auto [n, g] : gradient) EXPECT_NEAR(g, (value_plus[n] - value_minus[n]) / (2 * eps), 1e-6) << x;
  }
}

TEST(Shape, GradientIsTheDerivativeOfTheWeight) {
  check_gradient_is_derivative<LinearBasis>();
  check_gradient_is_derivative<QuadraticBSplineBasis>();
}

}  // namespace
