// The shape-function family (issue 3; Gong 2015 ch. 4 and 6, extraction §5 and tests U1, U3, U4,
// U8; Nairn 2026 §2.1): cubic B-spline, uGIMP, cpGIMP, B2GIMP, CPDI1, CPDI2, B2CPDI in 1-D, 2-D
// and 3-D. Every check includes particles in the cells next to the grid edge, whose stencils or
// domains reach past it (folded, shape/kernels.hpp), and one particle exactly on the grid corner.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/domains.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;

template <int D>
using Corners = typename ParticleSet<D>::Corners;

/// Test grid: origin -0.3, unequal spacings per axis, `cells` cells per axis, no ghost layers.
template <int D>
Grid<D> test_grid(int cells) {
  Vec<D> h;
  std::array<int, D> n{};
  for (int a = 0; a < D; ++a) {
    h[a] = 0.1 + 0.05 * a;
    n[a] = cells;
  }
  return Grid<D>(Vec<D>::Constant(-0.3), h, n, 0);
}

/// A deformation gradient I + 0.25 R with det > 0.5 (R uniform in [-1, 1]).
template <int D>
Mat<D> random_F(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (true) {
    Mat<D> F = Mat<D>::Identity();
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) F(i, j) += 0.25 * u(rng);
    if (F.determinant() > 0.5) return F;
  }
}

/// Moves each tracked corner by up to 20 % of the domain size (a random convex quadrilateral /
/// hexahedron) and puts the particle at the domain centroid (Gong eq. (6.29)).
template <int D>
void perturb_corners(ParticleSet<D>& ps, std::size_t p, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (auto& c : ps.corners[p])
    for (int a = 0; a < D; ++a) c[a] += u(rng) * ps.size0[p][a];
  std::array<double, (1 << D)> w;
  std::array<Vec<D>, (1 << D)> g;
  cpdi_coefficients<D>(ps.corners[p], w, g);
  Vec<D> centroid = Vec<D>::Zero();
  for (int c = 0; c < (1 << D); ++c) centroid += w[c] * ps.corners[p][c];
  ps.x[p] = centroid;
}

/// Random particles (a quarter in the first cell, a quarter in the last, one on the grid corner),
/// particle size 0.6 to 1 cell, random F (used by cpGIMP and CPDI1 / B2CPDI), random quadrilateral
/// domains when `tracked`.
template <int D>
ParticleSet<D> random_particles(const Grid<D>& grid, bool tracked, int count, unsigned seed) {
  ParticleSet<D> ps;
  ps.track_corners = tracked;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < count; ++k) {
    Vec<D> x, size;
    for (int a = 0; a < D; ++a) {
      double t = u(rng);
      if (k % 4 == 0) t = 0.02 * t;
      if (k % 4 == 1) t = 1.0 - 0.02 * t;
      x[a] = grid.origin[a] + t * grid.cells[a] * grid.h[a];
      size[a] = (0.6 + 0.4 * u(rng)) * grid.h[a];
    }
    if (k == 0) x = grid.origin;
    ps.add(x, Vec<D>::Zero(), 1.0, size.prod(), size, 0, 0);
    ps.F.back() = random_F<D>(rng);
    if (tracked) perturb_corners<D>(ps, ps.size() - 1, rng);
  }
  return ps;
}

struct NodeValue {
  double N = 0;
  std::vector<double> dN;
};

/// Weights and gradients of particle p, summed per node (a node may only appear once, checked).
template <int D, class Stencils>
std::map<Index, std::pair<double, Vec<D>>> node_weights(const Grid<D>& grid, const Stencils& st,
                                                        std::size_t p) {
  std::map<Index, std::pair<double, Vec<D>>> out;
  const auto [lo, hi] = st.node_span(grid, p);
  st.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
    EXPECT_GE(node, 0);
    EXPECT_LT(node, grid.node_count);
    EXPECT_GE(node, lo);
    EXPECT_LE(node, hi);
    EXPECT_EQ(out.count(node), 0u) << "node visited twice";
    out[node] = {N, dN};
  });
  return out;
}

/// Partition of unity, linear reproduction, zero gradient sum, exact gradient of a linear field.
template <int D, class Stencils>
void check_consistency(int cells, bool tracked, const char* name) {
  SCOPED_TRACE(std::string(name) + " D=" + std::to_string(D));
  const auto grid = test_grid<D>(cells);
  const auto ps = random_particles<D>(grid, tracked, 200, 11);
  Stencils st;
  st.evaluate(grid, ps);
  const Vec<D> slope = Vec<D>::LinSpaced(D, 1.5, -2.0);  // f(x) = 0.7 + slope . x
  for (std::size_t p = 0; p < ps.size(); ++p) {
    double sum = 0, f = 0;
    Vec<D> grad_sum = Vec<D>::Zero(), grad_f = Vec<D>::Zero(), moment = Vec<D>::Zero();
    for (const auto& [node, value] : node_weights<D>(grid, st, p)) {
      const auto& [N, dN] = value;
      const Vec<D> xi = grid.node_position(node);
      sum += N;
      grad_sum += dN;
      moment += N * xi;
      const double fi = 0.7 + slope.dot(xi);
      f += N * fi;
      grad_f += fi * dN;
    }
    ASSERT_NEAR(sum, 1.0, 1e-13) << "partition of unity, particle " << p;
    ASSERT_LT((moment - ps.x[p]).norm(), 1e-13) << "linear reproduction, particle " << p;
    ASSERT_NEAR(f, 0.7 + slope.dot(ps.x[p]), 1e-12);
    ASSERT_LT(grad_sum.norm(), 1e-11) << "gradients sum to zero, particle " << p;
    ASSERT_LT((grad_f - slope).norm(), 1e-11) << "gradient of a linear field, particle " << p;
  }
}

template <class Stencils1, class Stencils2, class Stencils3>
void check_all_dimensions(int cells, bool tracked, const char* name) {
  check_consistency<1, Stencils1>(cells, tracked, name);
  check_consistency<2, Stencils2>(cells, tracked, name);
  check_consistency<3, Stencils3>(cells, tracked, name);
}

template <template <int> class S>
void check_all(int cells, bool tracked, const char* name) {
  check_all_dimensions<S<1>, S<2>, S<3>>(cells, tracked, name);
}

template <int D>
using Cubic = TensorStencils<D, CubicBSplineBasis>;
template <int D>
using UGimp = TensorStencils<D, UGimpBasis>;
template <int D>
using CpGimp = TensorStencils<D, CpGimpBasis>;
template <int D>
using B2Gimp = TensorStencils<D, B2GimpBasis>;
template <int D>
using Cpdi1 = CpdiStencils<D, HatKernel, CpdiDomain::Parallelogram>;
template <int D>
using Cpdi2 = CpdiStencils<D, HatKernel, CpdiDomain::Tracked>;
template <int D>
using B2Cpdi = CpdiStencils<D, QuadraticKernel, CpdiDomain::Parallelogram>;

TEST(ShapeFamily, PartitionOfUnityLinearReproductionAndGradientSums) {
  for (int cells : {3, 6}) {  // 3: the fewest cells for the widest stencils, folds at both edges
    check_all<Cubic>(cells, false, "bspline3");
    check_all<UGimp>(cells, false, "ugimp");
    check_all<CpGimp>(cells, false, "cpgimp");
    check_all<B2Gimp>(cells, false, "b2gimp");
    check_all<Cpdi1>(cells, false, "cpdi1");
    check_all<Cpdi2>(cells, true, "cpdi2");
    check_all<B2Cpdi>(cells, false, "b2cpdi");
  }
}

/// U3 (and U1 for the point bases): dS/dx equals the central difference of S in the particle
/// position with the domain size held fixed, everywhere (the weights are C1 in x_p; the cubic C2).
template <int D, class Stencils>
void check_gradient_is_derivative(const char* name) {
  SCOPED_TRACE(std::string(name) + " D=" + std::to_string(D));
  const auto grid = test_grid<D>(5);
  auto base = random_particles<D>(grid, false, 60, 5);
  const double eps = 1e-7;
  for (std::size_t p = 0; p < base.size(); ++p) {
    ParticleSet<D> ps;
    for (int k = 0; k < 1 + 2 * D; ++k) {
      Vec<D> x = base.x[p];
      if (k > 0) x[(k - 1) / 2] += (k % 2 == 1 ? -eps : eps);
      ps.add(x, Vec<D>::Zero(), 1.0, 1.0, base.size0[p], 0, 0);
      ps.F.back() = base.F[p];
    }
    Stencils st;
    st.evaluate(grid, ps);
    const auto centre = node_weights<D>(grid, st, 0);
    for (int a = 0; a < D; ++a) {
      auto minus = node_weights<D>(grid, st, 1 + 2 * a), plus = node_weights<D>(grid, st, 2 + 2 * a);
      for (const auto& [node, value] : centre)
        EXPECT_NEAR(value.second[a], (plus[node].first - minus[node].first) / (2 * eps), 2e-6)
            << "particle " << p << " node " << node << " axis " << a;
    }
  }
}

TEST(ShapeFamily, GradientIsTheDerivativeOfTheWeight) {
  check_gradient_is_derivative<1, Cubic<1>>("bspline3");
  check_gradient_is_derivative<2, Cubic<2>>("bspline3");
  check_gradient_is_derivative<3, Cubic<3>>("bspline3");
  check_gradient_is_derivative<1, UGimp<1>>("ugimp");
  check_gradient_is_derivative<2, UGimp<2>>("ugimp");
  check_gradient_is_derivative<3, UGimp<3>>("ugimp");
  check_gradient_is_derivative<1, CpGimp<1>>("cpgimp");
  check_gradient_is_derivative<2, CpGimp<2>>("cpgimp");
  check_gradient_is_derivative<3, CpGimp<3>>("cpgimp");
  check_gradient_is_derivative<1, B2Gimp<1>>("b2gimp");
  check_gradient_is_derivative<2, B2Gimp<2>>("b2gimp");
  check_gradient_is_derivative<3, B2Gimp<3>>("b2gimp");
}

/// Gong 2015 §6.3 closed form of 1-D GIMP (extraction §5.2, h = 1, d = x_p - x_i), with the sign
/// of the last gradient branch corrected: the general antiderivative form must agree with it.
TEST(ShapeFamily, UGimpMatchesGongClosedFormWithCorrectedSign) {
  auto S = [](double d, double l) {
    if (d <= -1 - l) return 0.0;
    if (d <= -1 + l) return (1 + l + d) * (1 + l + d) / (4 * l);
    if (d <= -l) return 1 + d;
    if (d <= l) return 1 - (d * d + l * l) / (2 * l);
    if (d <= 1 - l) return 1 - d;
    if (d <= 1 + l) return (1 + l - d) * (1 + l - d) / (4 * l);
    return 0.0;
  };
  auto G = [](double d, double l) {
    if (d <= -1 - l) return 0.0;
    if (d <= -1 + l) return (1 + l + d) / (2 * l);
    if (d <= -l) return 1.0;
    if (d <= l) return -d / l;
    if (d <= 1 - l) return -1.0;
    if (d <= 1 + l) return -(1 + l - d) / (2 * l);  // the text prints "+": sign typo
    return 0.0;
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double xi = 3.0 + 4.0 * u(rng), l = 0.01 + 0.49 * u(rng);
    double w[4], dw[4];
    const int i0 = domain_on_grid<HatKernel>(xi, l, 20, w, dw);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(w[j], S(xi - (i0 + j), l), 1e-13);
      EXPECT_NEAR(dw[j], G(xi - (i0 + j), l), 1e-12);
    }
  }
}

/// U1: the per-particle windows equal the direct kernel evaluation at each node, inside the grid.
template <class Kernel>
void check_window_matches_kernel() {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(3.0, 7.0);
  for (int k = 0; k < 500; ++k) {
    const double xi = u(rng);
    double w[Kernel::point_width], dw[Kernel::point_width];
    const int i0 = point_on_grid<Kernel>(xi, 20, w, dw);
    double sum = 0;
    for (int j = 0; j < Kernel::point_width; ++j) {
      EXPECT_NEAR(w[j], Kernel::value(xi - (i0 + j)), 1e-15);
      sum += w[j];
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
    for (int j = -3; j < 0; ++j) EXPECT_EQ(Kernel::value(xi - (i0 + j)), 0.0);  // nothing left out
    for (int j = Kernel::point_width; j < Kernel::point_width + 3; ++j)
      EXPECT_EQ(Kernel::value(xi - (i0 + j)), 0.0);
  }
}

TEST(ShapeFamily, KernelWindowsEqualDirectEvaluation) {
  check_window_matches_kernel<HatKernel>();
  check_window_matches_kernel<QuadraticKernel>();
  check_window_matches_kernel<CubicKernel>();
}

/// Cox-de Boor evaluation of B-spline k of degree 3 on the knot vector t (right-continuous, with
/// the last interval closed).
double cox_de_boor(const std::vector<double>& t, int k, int degree, double x) {
  if (degree == 0) {
    const bool last = x == t.back() && t[k + 1] == t.back() && t[k] < t[k + 1];
    return (t[k] <= x && x < t[k + 1]) || last ? 1.0 : 0.0;
  }
  double v = 0;
  if (t[k + degree] > t[k]) v += (x - t[k]) / (t[k + degree] - t[k]) * cox_de_boor(t, k, degree - 1, x);
  if (t[k + degree + 1] > t[k + 1])
    v += (t[k + degree + 1] - x) / (t[k + degree + 1] - t[k + 1]) * cox_de_boor(t, k + 1, degree - 1, x);
  return v;
}

/// The boundary-modified cubic B-spline is the open (clamped) knot vector basis {0,0,0,0,1,...,
/// c,c,c,c} with the extra control points at h/3 and c - h/3 shared by linear interpolation.
TEST(ShapeFamily, CubicBSplineEqualsOpenKnotVectorBasis) {
  for (int c : {3, 4, 7}) {
    std::vector<double> t{0, 0, 0};
    for (int i = 0; i <= c; ++i) t.push_back(i);
    for (int i = 0; i < 3; ++i) t.push_back(c);
    for (int k = 0; k <= 200; ++k) {
      const double x = c * k / 200.0;
      std::vector<double> B(c + 3), N(c + 1, 0.0);
      for (int j = 0; j < c + 3; ++j) B[j] = cox_de_boor(t, j, 3, x);
      N[0] = B[0] + 2.0 / 3.0 * B[1];
      N[1] = B[2] + 1.0 / 3.0 * B[1];
      for (int j = 2; j <= c - 2; ++j) N[j] = B[j + 1];
      N[c - 1] = B[c] + 1.0 / 3.0 * B[c + 1];
      N[c] = B[c + 2] + 2.0 / 3.0 * B[c + 1];
      double w[4], dw[4];
      const int i0 = CubicBSplineBasis::evaluate(x, c, w, dw);
      std::vector<double> mine(c + 1, 0.0);
      for (int j = 0; j < 4; ++j) mine[i0 + j] = w[j];
      for (int j = 0; j <= c; ++j)
        EXPECT_NEAR(mine[j], N[j], 1e-14) << "c = " << c << " x = " << x << " node " << j;
    }
  }
}

// ---- CPDI corner coefficients against the papers' closed forms and against Gauss integration.

TEST(ShapeFamily, CpdiCoefficientsMatchGongClosedForms) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    // 1-D (Gong §6.6, eqs. (6.33)-(6.34) as fixed in extraction §5.5)
    {
      Corners<1> X{Vec<1>(0.3 + 0.1 * u(rng)), Vec<1>(0.7 + 0.1 * u(rng))};
      std::array<double, 2> w;
      std::array<Vec<1>, 2> g;
      EXPECT_NEAR(cpdi_coefficients<1>(X, w, g), X[1][0] - X[0][0], 1e-15);
      EXPECT_NEAR(w[0], 0.5, 1e-15);
      EXPECT_NEAR(w[1], 0.5, 1e-15);
      EXPECT_NEAR(g[0][0], -1.0 / (X[1][0] - X[0][0]), 1e-12);
      EXPECT_NEAR(g[1][0], 1.0 / (X[1][0] - X[0][0]), 1e-12);
    }
    // CPDI1 parallelogram (eqs. (6.26)-(6.27), full edge vectors r1, r2)
    {
      const Vec<2> xp(u(rng), u(rng)), r1(1.0 + 0.3 * u(rng), 0.3 * u(rng)),
          r2(0.3 * u(rng), 1.0 + 0.3 * u(rng));
      // tensor order c0 = x1, c1 = x2, c3 = x3, c2 = x4 (counter-clockwise x1..x4 of extraction §5.3)
      Corners<2> X{xp - 0.5 * (r1 + r2), xp + 0.5 * (r1 - r2), xp - 0.5 * (r1 - r2), xp + 0.5 * (r1 + r2)};
      std::array<double, 4> w;
      std::array<Vec<2>, 4> g;
      const double area = cpdi_coefficients<2>(X, w, g);
      EXPECT_NEAR(area, r1[0] * r2[1] - r1[1] * r2[0], 1e-14);
      for (double wc : w) EXPECT_NEAR(wc, 0.25, 1e-15);
      const Vec<2> g1 = Vec<2>(r1[1] - r2[1], r2[0] - r1[0]) / (2 * area);
      const Vec<2> g2 = Vec<2>(r1[1] + r2[1], -r1[0] - r2[0]) / (2 * area);
      EXPECT_LT((g[0] - g1).norm(), 1e-13);
      EXPECT_LT((g[3] + g1).norm(), 1e-13);
      EXPECT_LT((g[1] - g2).norm(), 1e-13);
      EXPECT_LT((g[2] + g2).norm(), 1e-13);
    }
    // CPDI2 quadrilateral (§6.5 with "(1 - a - b)" read as 6Ω - a - b, eq. (6.32))
    {
      std::array<Vec<2>, 4> x{Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)};  // CCW x1..x4
      for (auto& c : x) c += 0.25 * Vec<2>(u(rng), u(rng));
      Corners<2> X{x[0], x[1], x[3], x[2]};
      std::array<double, 4> w;
      std::array<Vec<2>, 4> g;
      const double area = cpdi_coefficients<2>(X, w, g);
      const double a = (x[3][0] - x[0][0]) * (x[1][1] - x[2][1]) - (x[1][0] - x[2][0]) * (x[3][1] - x[0][1]);
      const double b = (x[2][0] - x[3][0]) * (x[0][1] - x[1][1]) - (x[0][0] - x[1][0]) * (x[2][1] - x[3][1]);
      const double shoelace =
          0.5 * ((x[2] - x[0])[0] * (x[3] - x[1])[1] - (x[2] - x[0])[1] * (x[3] - x[1])[0]);
      EXPECT_NEAR(area, shoelace, 1e-14);
      EXPECT_NEAR(w[0], (6 * area - a - b) / (24 * area), 1e-14);
      EXPECT_NEAR(w[1], (6 * area - a + b) / (24 * area), 1e-14);
      EXPECT_NEAR(w[3], (6 * area + a + b) / (24 * area), 1e-14);
      EXPECT_NEAR(w[2], (6 * area + a - b) / (24 * area), 1e-14);
      const Vec<2> A = Vec<2>(x[1][1] - x[3][1], x[3][0] - x[1][0]) / (2 * area);
      const Vec<2> B = Vec<2>(x[2][1] - x[0][1], x[0][0] - x[2][0]) / (2 * area);
      EXPECT_LT((g[0] - A).norm(), 1e-13);
      EXPECT_LT((g[1] - B).norm(), 1e-13);
      EXPECT_LT((g[3] + A).norm(), 1e-13);
      EXPECT_LT((g[2] + B).norm(), 1e-13);
    }
  }
}

/// U4: the CPDI weights and gradients equal the integrals over the particle domain of the grid
/// function's multilinear interpolant from the corners, S = (1/V) int sum_c N^p_c(x) N_i(x_c) dx and
/// grad S = (1/V) int sum_c grad N^p_c(x) N_i(x_c) dx, computed here with a 5-point Gauss rule per
/// axis on the isoparametric domain (exact to degree 9), for random quadrilaterals / hexahedra
/// (CPDI2) and parallelograms (CPDI1, B2CPDI), next to the grid edge included.
template <int D, class Stencils>
void check_against_gauss(bool tracked, const char* name) {
  SCOPED_TRACE(std::string(name) + " D=" + std::to_string(D));
  using Kernel = std::conditional_t<Stencils::W == 2, HatKernel, QuadraticKernel>;
  constexpr int C = 1 << D;
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                        0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                        0.2369268850561891};
  const auto grid = test_grid<D>(4);
  const auto ps = random_particles<D>(grid, tracked, 80, 17);
  Stencils st;
  st.evaluate(grid, ps);
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto X = Stencils::corners(ps, p);
    // N_i(x_c) of every corner, by node.
    std::array<std::map<Index, double>, C> Nc;
    for (int c = 0; c < C; ++c) {
      std::array<int, D> i0;
      double w[D][Kernel::point_width], dw[Kernel::point_width];
      for (int a = 0; a < D; ++a)
        i0[a] = point_on_grid<Kernel>((X[c][a] - grid.origin[a]) / grid.h[a], grid.cells[a], w[a], dw);
      int total = 1;
      for (int a = 0; a < D; ++a) total *= Kernel::point_width;
      for (int m = 0; m < total; ++m) {
        std::array<int, D> ijk;
        double N = 1;
        for (int a = 0, r = m; a < D; ++a, r /= Kernel::point_width) {
          ijk[a] = i0[a] + r % Kernel::point_width;
          N *= w[a][r % Kernel::point_width];
        }
        Nc[c][grid.node_index(ijk)] += N;
      }
    }
    std::map<Index, std::pair<double, Vec<D>>> ref;
    double volume = 0;
    int points = 1;
    for (int a = 0; a < D; ++a) points *= 5;
    for (int q = 0; q < points; ++q) {
      Vec<D> xi;
      double wq = 1;
      for (int a = 0, r = q; a < D; ++a, r /= 5) {
        xi[a] = gx[r % 5];
        wq *= gw[r % 5];
      }
      std::array<double, C> N;
      std::array<Vec<D>, C> dN;
      Mat<D> J = Mat<D>::Zero();
      for (int c = 0; c < C; ++c) {
        N[c] = 1;
        for (int a = 0; a < D; ++a) N[c] *= 0.5 * (1 + ((c >> a & 1) ? xi[a] : -xi[a]));
        for (int a = 0; a < D; ++a) {
          dN[c][a] = (c >> a & 1) ? 0.5 : -0.5;
          for (int b = 0; b < D; ++b)
            if (b != a) dN[c][a] *= 0.5 * (1 + ((c >> b & 1) ? xi[b] : -xi[b]));
        }
        J += X[c] * dN[c].transpose();
      }
      const double det = J.determinant();
      const Mat<D> JinvT = J.inverse().transpose();
      volume += wq * det;
      for (int c = 0; c < C; ++c)
        for (const auto& [node, value] : Nc[c]) {
          auto& r = ref.try_emplace(node, 0.0, Vec<D>::Zero()).first->second;
          r.first += wq * det * N[c] * value;
          r.second += wq * det * value * (JinvT * dN[c]);
        }
    }
    const auto mine = node_weights<D>(grid, st, p);
    for (const auto& [node, value] : ref) {
      const double S = value.first / volume;
      const Vec<D> G = value.second / volume;
      const auto it = mine.find(node);
      if (it == mine.end()) {
        EXPECT_LT(std::abs(S) + G.norm(), 1e-12) << "missing node " << node;
        continue;
      }
      EXPECT_NEAR(it->second.first, S, 1e-13) << "particle " << p << " node " << node;
      EXPECT_LT((it->second.second - G).norm(), 1e-10 * (1 + G.norm()))
          << "particle " << p << " node " << node;
    }
    for (const auto& [node, value] : mine)
      if (!ref.count(node)) {
        EXPECT_LT(std::abs(value.first) + value.second.norm(), 1e-12);
      }
  }
}

TEST(ShapeFamily, CpdiEqualsGaussIntegrationOverTheDomain) {
  check_against_gauss<1, Cpdi1<1>>(false, "cpdi1");
  check_against_gauss<2, Cpdi1<2>>(false, "cpdi1");
  check_against_gauss<3, Cpdi1<3>>(false, "cpdi1");
  check_against_gauss<1, Cpdi2<1>>(true, "cpdi2");
  check_against_gauss<2, Cpdi2<2>>(true, "cpdi2");
  check_against_gauss<3, Cpdi2<3>>(true, "cpdi2");
  check_against_gauss<1, B2Cpdi<1>>(false, "b2cpdi");
  check_against_gauss<2, B2Cpdi<2>>(false, "b2cpdi");
  check_against_gauss<3, B2Cpdi<3>>(false, "b2cpdi");
}

/// For an axis-aligned domain inside one cell the bilinear hat is its own interpolant, so CPDI1
/// and uGIMP give the same weights (a cross-check between the two families).
TEST(ShapeFamily, CpdiEqualsGimpForAnAxisAlignedDomainInsideOneCell) {
  const auto grid = test_grid<2>(4);
  ParticleSet<2> ps;
  const Vec<2> size = 0.3 * grid.h;
  ps.add(grid.origin + Vec<2>(1.5 * grid.h[0], 2.4 * grid.h[1]), Vec<2>::Zero(), 1, size.prod(), size, 0, 0);
  Cpdi1<2> cpdi;
  UGimp<2> gimp;
  cpdi.evaluate(grid, ps);
  gimp.evaluate(grid, ps);
  const auto a = node_weights<2>(grid, cpdi, 0), b = node_weights<2>(grid, gimp, 0);
  for (const auto& [node, value] : b) {
    const auto it = a.find(node);  // the CPDI box holds only the 2 x 2 nodes of the cell
    const double N = it == a.end() ? 0.0 : it->second.first;
    const Vec<2> dN = it == a.end() ? Vec<2>::Zero() : it->second.second;
    EXPECT_NEAR(N, value.first, 1e-14);
    EXPECT_LT((dN - value.second).norm(), 1e-12);
  }
}

// ---- Whole steps: rigid translation (U8) and the two-disks collision with every basis.

const std::vector<std::pair<ShapeKind, const char*>> kDomainAndNewBases{
    {ShapeKind::BSpline3, "bspline3"}, {ShapeKind::UGIMP, "ugimp"}, {ShapeKind::CpGIMP, "cpgimp"},
    {ShapeKind::B2GIMP, "b2gimp"},     {ShapeKind::CPDI1, "cpdi1"}, {ShapeKind::CPDI2, "cpdi2"},
    {ShapeKind::B2CPDI, "b2cpdi"}};

/// A block filling the first cells of the grid (its particle domains touch the min faces) that
/// moves with uniform velocity v, no loads, no conditions.
Spec rigid_block_spec(int dim, ShapeKind shape, UpdateScheme scheme) {
  Spec spec;
  spec.grid.dim = dim;
  for (int a = 0; a < dim; ++a) {
    spec.grid.min[a] = 0;
    spec.grid.max[a] = 1;
    spec.grid.cell_size[a] = 0.125;
    spec.grid.cells[a] = 8;
  }
  MaterialSpec m;
  m.name = "m";
  m.density = 1000;
  m.youngs_modulus = 1e6;
  m.poisson_ratio = 0.3;
  m.lambda = 1e6 * 0.3 / (1.3 * 0.4);
  m.mu = 1e6 / 2.6;
  spec.materials.push_back(m);
  BodySpec b;
  b.name = "block";
  for (int a = 0; a < dim; ++a) {
    b.min[a] = 0.0;
    b.max[a] = 0.375;
    b.velocity[a] = 0.5 - 0.2 * a;
  }
  b.particles_per_cell = 2;
  spec.bodies.push_back(b);
  spec.solver.shape = shape;
  spec.solver.scheme = scheme;
  spec.solver.dt = 1e-3;
  spec.solver.end_time = 0.1;
  return spec;
}

template <int D, class Stencils>
void check_rigid_translation(ShapeKind shape, UpdateScheme scheme, const char* name) {
  SCOPED_TRACE(std::string(name) + " D=" + std::to_string(D));
  const Spec spec = rigid_block_spec(D, shape, scheme);
  auto sim = build_simulation<D>(spec);
  const auto x0 = sim.particles.x;
  const auto id0 = sim.particles.id;
  ExplicitStepper<D, Stencils> stepper(sim);
  const int steps = 100;
  for (int k = 0; k < steps; ++k) stepper.step(1e-3);
  Vec<D> v;
  for (int a = 0; a < D; ++a) v[a] = 0.5 - 0.2 * a;
  std::map<long, Vec<D>> start;
  for (std::size_t p = 0; p < x0.size(); ++p) start[id0[p]] = x0[p];
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    ASSERT_LT(sim.particles.stress[p].norm(), 1e-10 * 1e6) << "stress of a rigid translation (E = 1e6)";
    ASSERT_LT((sim.particles.x[p] - start[sim.particles.id[p]] - v * (steps * 1e-3)).norm(), 1e-12);
    ASSERT_LT((sim.particles.v[p] - v).norm(), 1e-10);  // FLIP adds (v+ - v)/dt dt: round-off / dt per step
    ASSERT_LT((sim.particles.F[p] - Mat<D>::Identity()).norm(), 1e-10);
  }
}

template <int D>
void rigid_translation_all(UpdateScheme scheme) {
  check_rigid_translation<D, Cubic<D>>(ShapeKind::BSpline3, scheme, "bspline3");
  check_rigid_translation<D, UGimp<D>>(ShapeKind::UGIMP, scheme, "ugimp");
  check_rigid_translation<D, CpGimp<D>>(ShapeKind::CpGIMP, scheme, "cpgimp");
  check_rigid_translation<D, B2Gimp<D>>(ShapeKind::B2GIMP, scheme, "b2gimp");
  check_rigid_translation<D, Cpdi1<D>>(ShapeKind::CPDI1, scheme, "cpdi1");
  check_rigid_translation<D, Cpdi2<D>>(ShapeKind::CPDI2, scheme, "cpdi2");
  check_rigid_translation<D, B2Cpdi<D>>(ShapeKind::B2CPDI, scheme, "b2cpdi");
}

TEST(ShapeFamily, RigidTranslationIsExactNextToTheGridEdge) {
  for (auto scheme : {UpdateScheme::USL, UpdateScheme::MUSL}) {
    rigid_translation_all<1>(scheme);
    rigid_translation_all<2>(scheme);
    rigid_translation_all<3>(scheme);
  }
}

/// CPDI2 corners follow a rigid translation and a uniform stretch exactly.
TEST(ShapeFamily, Cpdi2CornersMoveWithTheGridVelocity) {
  Spec spec = rigid_block_spec(2, ShapeKind::CPDI2, UpdateScheme::USL);
  auto sim = build_simulation<2>(spec);
  const auto before = sim.particles.corners;
  const auto id0 = sim.particles.id;
  ExplicitStepper<2, Cpdi2<2>> stepper(sim);
  for (int k = 0; k < 50; ++k) stepper.step(1e-3);
  std::map<long, Corners<2>> start;
  for (std::size_t p = 0; p < before.size(); ++p) start[id0[p]] = before[p];
  const Vec<2> shift = 0.05 * Vec<2>(0.5, 0.3);
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    for (int c = 0; c < 4; ++c)
      ASSERT_LT((sim.particles.corners[p][c] - start[sim.particles.id[p]][c] - shift).norm(), 1e-12);
}

/// Two disks (examples/two-disks, MUSL + FLIP) with every new basis: momentum is conserved to
/// round-off (no condition touches the disks) and the total energy stays within 1 % to t = 3, the
/// issue's bound for MUSL with the quadratic B-spline (measured for these bases: 0.12 - 0.14 %).
TEST(ShapeFamily, TwoDisksConserveMomentumAndBoundEnergyWithEveryBasis) {
  for (const auto& [shape, name] : kDomainAndNewBases) {
    SCOPED_TRACE(name);
    Spec spec = test::load_example("two-disks");
    spec.solver.shape = shape;
    spec.solver.scheme = UpdateScheme::MUSL;
    spec.solver.transfer = VelocityTransfer::FLIP;
    spec.solver.end_time = 3.0;
    const auto result = test::run_quietly(spec, std::string("family_disks_") + name);
    ASSERT_EQ(result.exit_code, 0) << result.message;
    EXPECT_LT(test::measured(result, "max_relative_momentum_error"), 1e-10);
    EXPECT_LT(test::measured(result, "max_relative_energy_error"), 0.01);
    EXPECT_GT(test::measured(result, "min_jacobian"), 0.0);
  }
}

/// Domain output: domains_NNNNNN.vtu (+ domains.pvd) with one cell per particle for the domain
/// bases, none for the point bases.
TEST(ShapeFamily, DomainBasesWriteTheirDomainsForParaView) {
  for (auto [shape, name] :
       {std::pair{ShapeKind::CPDI2, "cpdi2"}, std::pair{ShapeKind::BSpline3, "bspline3"}}) {
    Spec spec = rigid_block_spec(3, shape, UpdateScheme::MUSL);
    spec.solver.end_time = 0.002;
    spec.output.plots = false;
    RunOptions options;
    options.out_dir = matpoint::test::scratch_folder(std::string("domains_") + name);
    std::filesystem::remove_all(options.out_dir);
    options.progress = false;
    const auto result = run_explicit(spec, options);
    ASSERT_EQ(result.exit_code, 0);
    const auto file = options.out_dir / "domains_000000.vtu";
    if (shape == ShapeKind::BSpline3) {
      EXPECT_FALSE(std::filesystem::exists(file));
      continue;
    }
    ASSERT_TRUE(std::filesystem::exists(file));
    ASSERT_TRUE(std::filesystem::exists(options.out_dir / "domains.pvd"));
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const std::string expected =
        "NumberOfPoints=\"" + std::to_string(8 * result.summary["particles"].get<long>()) +
        "\" NumberOfCells=\"" + std::to_string(result.summary["particles"].get<long>()) + "\"";
    EXPECT_NE(text.str().find(expected), std::string::npos);
    std::filesystem::remove_all(options.out_dir);
  }
}

// ---- Input: solver.basis names and the grid size each basis needs.

std::string input_with_shape(const std::string& shape, double cell_size) {
  return R"({"grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": )" + std::to_string(cell_size) +
         R"(},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e6, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0, 0], "max": [0.5, 0.5]}}],
  "solver": {"basis": ")" +
         shape + R"(", "end_time": 1}})";
}

TEST(ShapeFamily, InputAcceptsEveryShapeName) {
  const std::pair<const char*, ShapeKind> names[] = {
      {"linear", ShapeKind::Linear}, {"bspline2", ShapeKind::BSpline2}, {"bspline3", ShapeKind::BSpline3},
      {"ugimp", ShapeKind::UGIMP},   {"cpgimp", ShapeKind::CpGIMP},     {"cpdi1", ShapeKind::CPDI1},
      {"cpdi2", ShapeKind::CPDI2},   {"b2gimp", ShapeKind::B2GIMP},     {"b2cpdi", ShapeKind::B2CPDI}};
  for (const auto& [name, kind] : names)
    EXPECT_EQ(parse_spec(input_with_shape(name, 0.25)).solver.shape, kind);
  EXPECT_THROW((void)parse_spec(input_with_shape("cpdi3", 0.25)), InputError);
}

TEST(ShapeFamily, TooFewCellsForTheStencilIsAnInputError) {
  EXPECT_THROW((void)build_simulation<2>(parse_spec(input_with_shape("bspline3", 0.5))), InputError);
  EXPECT_THROW((void)build_simulation<2>(parse_spec(input_with_shape("b2gimp", 0.5))), InputError);
  EXPECT_NO_THROW((void)build_simulation<2>(parse_spec(input_with_shape("ugimp", 0.5))));
  EXPECT_NO_THROW((void)build_simulation<2>(parse_spec(input_with_shape("cpdi2", 1.0))));
}

}  // namespace
