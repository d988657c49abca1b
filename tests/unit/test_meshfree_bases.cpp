// MLS and LME shape functions of the Galerkin meshfree method (Iaconeta et al. 2017 §4.2,
// eqs. (50)-(61); extraction §9.2 U-5) and the neighbour search that builds their clouds. Every
// expected value is an analytic identity: partition of unity and linear reproduction (eqs. (57)),
// their gradients (58), positivity with reproduction (LME's weak Kronecker-delta property), the
// large-gamma limit of LME (Arroyo & Ortiz 2006 §4: the Delaunay interpolant), and central finite
// differences of the functions themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "matpoint/shape/meshfree_lme.hpp"
#include "matpoint/shape/meshfree_mls.hpp"
#include "matpoint/shape/neighbour_search.hpp"

namespace {

using namespace matpoint;

/// Nodes of a regular grid with spacing h and n nodes per side, origin o, each moved by up to
/// jitter * h in every direction (a distorted cloud, as after deformation).
template <int D>
std::vector<Vec<D>> grid_nodes(int n, double h, double jitter, unsigned seed, double o = 0.3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<Vec<D>> x;
  std::array<int, D> i{};
  while (true) {
    Vec<D> p;
    for (int a = 0; a < D; ++a) p[a] = o + h * (i[a] + u(rng));
    x.push_back(p);
    int a = 0;
    while (a < D && ++i[a] == n) i[a] = 0, ++a;
    if (a == D) break;
  }
  return x;
}

template <int D>
std::vector<Vec<D>> cloud_of(const Vec<D>& x, const std::vector<Vec<D>>& nodes, double R) {
  std::vector<Vec<D>> c;
  for (const auto& y : nodes)
    if ((y - x).norm() < R) c.push_back(y);
  return c;
}

/// The shape functions of one basis at x for a fixed cloud (the cloud does not follow x, so that
/// finite differences differentiate the functions and not the cloud's membership).
template <int D>
using Evaluator = std::function<MeshfreeStatus(const Vec<D>&, const std::vector<Vec<D>>&,
                                               std::vector<double>&, std::vector<Vec<D>>&)>;

template <int D>
Evaluator<D> mls(double dilation, MlsWeight form = MlsWeight::Truncated, double radius = 0.0) {
  return [dilation, form, radius](const Vec<D>& x, const std::vector<Vec<D>>& c, std::vector<double>& N,
                                  std::vector<Vec<D>>& dN) {
    N.resize(c.size()), dN.resize(c.size());
    return mls_shape_functions<D>(x, c, dilation, N, dN, form, radius);
  };
}

template <int D>
Evaluator<D> lme(double beta) {
  return
      [beta](const Vec<D>& x, const std::vector<Vec<D>>& c, std::vector<double>& N, std::vector<Vec<D>>& dN) {
        N.resize(c.size()), dN.resize(c.size());
        LmeParameters p;
        p.beta = beta;
        return lme_shape_functions<D>(x, c, p, N, dN).status;
      };
}

/// Eqs. (57)-(58) at random points inside a distorted grid, and central differences of N.
template <int D>
void check_consistency(const Evaluator<D>& eval, double h, double R, int points, double fd_tol) {
  const int n = D == 2 ? 12 : 7;
  const auto nodes = grid_nodes<D>(n, h, 0.3, 11);
  std::mt19937 rng(7);
  // Points at least R from the grid's edge: full clouds (the hull contains x for LME).
  std::uniform_real_distribution<double> u(0.3 + R, 0.3 + (n - 1) * h - R);
  std::vector<double> N, Np, Nm;
  std::vector<Vec<D>> dN, scratch;
  for (int k = 0; k < points; ++k) {
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = u(rng);
    const auto c = cloud_of<D>(x, nodes, R);
    ASSERT_EQ(eval(x, c, N, dN), MeshfreeStatus::Ok) << "point " << k;
    double sum = 0.0;
    Vec<D> reproduced = Vec<D>::Zero(), sum_grad = Vec<D>::Zero();
    Mat<D> grad_x = Mat<D>::Zero();
    for (std::size_t i = 0; i < c.size(); ++i) {
      sum += N[i];
      reproduced += N[i] * c[i];
      sum_grad += dN[i];
      grad_x += c[i] * dN[i].transpose();
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "partition of unity, point " << k;
    EXPECT_LT((reproduced - x).norm(), 1e-12 * h) << "linear reproduction, point " << k;
    EXPECT_LT(sum_grad.norm() * h, 1e-10) << "sum grad N = 0, point " << k;
    EXPECT_LT((grad_x - Mat<D>::Identity()).norm(), 1e-10) << "sum x_I grad N_I^T = 1, point " << k;
    // Central differences, step 1e-5 h: truncation ~1e-10 / h, round-off ~1e-13 / 1e-5 h.
    const double eps = 1e-5 * h;
    for (int a = 0; a < D; ++a) {
      Vec<D> e = Vec<D>::Zero();
      e[a] = eps;
      ASSERT_EQ(eval(x + e, c, Np, scratch), MeshfreeStatus::Ok);
      ASSERT_EQ(eval(x - e, c, Nm, scratch), MeshfreeStatus::Ok);
      for (std::size_t i = 0; i < c.size(); ++i)
        EXPECT_NEAR(dN[i][a], (Np[i] - Nm[i]) / (2 * eps), fd_tol / h) << "node " << i << " axis " << a;
    }
  }
}

const double kR = 2.0 * std::sqrt(2.0);  // R / h, extraction A5

TEST(MeshfreeMls, ConsistencyAndGradients2D) {
  check_consistency<2>(mls<2>(0.2 * std::sqrt(2.0)), 0.2, kR * 0.2, 40, 1e-6);
}
TEST(MeshfreeMls, ConsistencyAndGradients3D) {
  check_consistency<3>(mls<3>(0.2 * std::sqrt(2.0)), 0.2, kR * 0.2, 15, 1e-6);
}
// The smooth weight (the Gaussian less its tangent at R, C1 there; meshfree_mls.hpp) keeps eqs.
// (57)-(58) and gradients that match central differences, with the cut R = 2 R_eff.
TEST(MeshfreeMls, SmoothWeightConsistencyAndGradients2D) {
  check_consistency<2>(mls<2>(0.2 * std::sqrt(2.0), MlsWeight::Smooth, kR * 0.2), 0.2, kR * 0.2, 40, 1e-6);
}
TEST(MeshfreeMls, SmoothWeightConsistencyAndGradients3D) {
  check_consistency<3>(mls<3>(0.2 * std::sqrt(2.0), MlsWeight::Smooth, kR * 0.2), 0.2, kR * 0.2, 15, 1e-6);
}

/// The largest change of any other node's N and h |grad N| when node `mover` of the cloud goes from
/// just inside R (distance R (1 - eps), in the cloud) to just outside (out of the cloud).
double largest_jump_across_the_cut(MlsWeight form, double eps, bool gradient) {
  const double h = 0.2, R = kR * h, dilation = R / 2;
  auto nodes = grid_nodes<2>(12, h, 0.3, 5);
  const Vec<2> x(1.23, 1.17);
  auto c = cloud_of<2>(x, nodes, R);
  c.push_back(x + Vec<2>(0.6, 0.8) * R * (1.0 - eps));  // the mover, last
  std::vector<double> N_in, N_out;
  std::vector<Vec<2>> dN_in, dN_out;
  const auto eval = mls<2>(dilation, form, R);
  EXPECT_EQ(eval(x, c, N_in, dN_in), MeshfreeStatus::Ok);
  c.pop_back();
  EXPECT_EQ(eval(x, c, N_out, dN_out), MeshfreeStatus::Ok);
  double jump = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i)
    jump = std::max(jump, gradient ? h * (dN_in[i] - dN_out[i]).norm() : std::abs(N_in[i] - N_out[i]));
  return jump;
}

// A node crossing the cut radius R changes the other nodes' functions continuously with the
// smooth weight: W ~ (s_R - s)^2 and grad W ~ (s_R - s) near R, so at distance R (1 - eps) the jumps
// are O(eps^2) in N and O(eps) in grad N (both shrink 100 and 10 times from eps = 1e-3 to 1e-4).
// The truncated Gaussian jumps by a fixed amount, W(R) = exp(-4) = 1.8 % of its peak (the energy
// source of docs/theory/implicit.md).
TEST(MeshfreeMls, SmoothWeightIsContinuousAcrossTheCutRadius) {
  const double n3 = largest_jump_across_the_cut(MlsWeight::Smooth, 1e-3, false),
               n4 = largest_jump_across_the_cut(MlsWeight::Smooth, 1e-4, false),
               g3 = largest_jump_across_the_cut(MlsWeight::Smooth, 1e-3, true),
               g4 = largest_jump_across_the_cut(MlsWeight::Smooth, 1e-4, true);
  std::printf("smooth weight, jumps at eps = 1e-3 / 1e-4: N %.3g / %.3g, h grad N %.3g / %.3g\n", n3, n4, g3,
              g4);
  EXPECT_LT(n4, 1e-6);
  EXPECT_NEAR(n3 / n4, 100.0, 5.0);  // O(eps^2)
  EXPECT_LT(g4, 1e-3);
  EXPECT_NEAR(g3 / g4, 10.0, 0.5);  // O(eps)
  const double t4 = largest_jump_across_the_cut(MlsWeight::Truncated, 1e-4, false);
  std::printf("truncated weight, jump at eps = 1e-4: N %.3g\n", t4);
  EXPECT_GT(t4, 1e-3);  // a fixed jump: the cut-off weight exp(-4) of the mover
}

TEST(MeshfreeLme, ConsistencyAndGradients2D) {
  check_consistency<2>(lme<2>(1.8 / 0.04), 0.2, kR * 0.2, 40, 1e-6);
}
TEST(MeshfreeLme, ConsistencyAndGradients3D) {
  check_consistency<3>(lme<3>(1.8 / 0.04), 0.2, kR * 0.2, 15, 1e-6);
}
// gamma = 0.8 (the widest of the rolling disk, extraction §6.4) and 4 (near the FE limit).
TEST(MeshfreeLme, ConsistencyAtOtherGammas) {
  check_consistency<2>(lme<2>(0.8 / 0.04), 0.2, kR * 0.2, 10, 1e-6);
  check_consistency<2>(lme<2>(4.0 / 0.04), 0.2, kR * 0.2, 10, 1e-6);
}

// Weak Kronecker delta (Arroyo & Ortiz 2006 §3.3): LME functions are non-negative and reproduce
// linear fields, so at a point at distance delta from a face of the cloud's convex hull the
// functions of the nodes off that face sum to at most delta / (the least distance of such a node
// from the face); on the face they vanish. At a hull vertex the vertex's own function tends to 1.
TEST(MeshfreeLme, WeakKroneckerDeltaOnTheHullBoundary) {
  const double h = 0.1;
  const auto nodes = grid_nodes<2>(11, h, 0.0, 1, 0.0);  // [0, 1]^2
  std::vector<double> N;
  std::vector<Vec<2>> dN;
  const auto eval = lme<2>(1.8 / (h * h));
  for (double delta : {1e-2, 1e-3, 1e-4}) {
    // Edge y = 0, between nodes: every node with y_a >= h has sum N_a <= delta.
    const Vec<2> xe(0.43, delta * h);
    const auto ce = cloud_of<2>(xe, nodes, kR * h);
    ASSERT_EQ(eval(xe, ce, N, dN), MeshfreeStatus::Ok) << delta;
    double off = 0.0;
    for (std::size_t i = 0; i < ce.size(); ++i) {
      EXPECT_GE(N[i], 0.0);
      if (ce[i][1] > 0.5 * h) off += N[i];
    }
    EXPECT_LE(off, delta * (1 + 1e-9)) << "edge, delta " << delta;
    EXPECT_GT(off, 0.0);
    // Corner (0, 0) along the bisector: sum_{a != corner} N_a (x_a . n) = x . n with x_a . n >= h / sqrt(2)
    // gives 1 - N_corner <= 2 delta.
    const Vec<2> xc(delta * h, delta * h);
    const auto cc = cloud_of<2>(xc, nodes, kR * h);
    ASSERT_EQ(eval(xc, cc, N, dN), MeshfreeStatus::Ok) << delta;
    for (std::size_t i = 0; i < cc.size(); ++i)
      if (cc[i].norm() < 1e-12) {
        EXPECT_GE(N[i], 1.0 - 2.0 * delta * (1 + 1e-9)) << "corner, delta " << delta;
      }
  }
}

/// Largest |N_LME - N_limit| over a few points for an interpolant `limit` of the nodes.
template <class Limit>
double distance_to_limit(const std::vector<Vec<2>>& nodes, double h, double gamma,
                         const std::vector<Vec<2>>& xs, Limit&& limit) {
  std::vector<double> N;
  std::vector<Vec<2>> dN;
  double worst = 0.0;
  for (const auto& x : xs) {
    const auto c = cloud_of<2>(x, nodes, kR * h);
    EXPECT_EQ(lme<2>(gamma / (h * h))(x, c, N, dN), MeshfreeStatus::Ok);
    for (std::size_t i = 0; i < c.size(); ++i) worst = std::max(worst, std::abs(N[i] - limit(c[i], x)));
  }
  return worst;
}

// Large gamma on a square grid: the Delaunay cell of x is its square, whose four corners are
// co-circular, so U = sum N_a |x - x_a|^2 (eq. (60)) is the same for every feasible N on them and
// the entropy (59) picks among those: the maximum-entropy distribution on {0,1}^2 with mean
// (s, t) is the product of two Bernoulli distributions, i.e. the bilinear Q4 functions (not the
// P1 hats of either diagonal's triangulation). The limit is reached exponentially in gamma.
TEST(MeshfreeLme, LargeGammaTendsToBilinearOnASquareGrid) {
  const double h = 0.1;
  const auto nodes = grid_nodes<2>(11, h, 0.0, 1, 0.0);
  const std::vector<Vec<2>> xs{{0.43, 0.56}, {0.51, 0.38}, {0.47, 0.42}};  // inside cells, off the edges
  auto q4 = [h](const Vec<2>& xa, const Vec<2>& x) {
    double w = 1.0;
    for (int a = 0; a < 2; ++a) w *= std::max(0.0, 1.0 - std::abs(x[a] - xa[a]) / h);
    return w;
  };
  double previous = 1.0;
  for (double gamma : {4.0, 8.0, 16.0, 32.0}) {
    const double e = distance_to_limit(nodes, h, gamma, xs, q4);
    std::printf("gamma %g  max |N_LME - N_Q4| = %.3g\n", gamma, e);
    EXPECT_LT(e, previous) << "gamma " << gamma;
    previous = e;
  }
  EXPECT_LT(previous, 1e-9) << "gamma 32";
}

// On a lattice of equilateral triangles the Delaunay triangulation is unique and the limit is the
// P1 hat function (barycentric coordinates of x in its triangle).
TEST(MeshfreeLme, LargeGammaTendsToP1OnATriangularLattice) {
  const double h = 0.1, k = std::sqrt(3.0) / 2.0;
  std::vector<Vec<2>> nodes;
  for (int j = 0; j < 13; ++j)
    for (int i = 0; i < 12; ++i) nodes.emplace_back(h * (i + 0.5 * (j % 2)), h * k * j);
  // x in the triangle (a, b, c) with a = (0.5, 6hk), b = a + (h, 0), c = a + (h/2, hk) (row 6 is even).
  const Vec<2> a(0.5, 6 * h * k), b = a + Vec<2>(h, 0.0), c = a + Vec<2>(0.5 * h, h * k);
  const std::vector<Vec<2>> bary{{0.2, 0.5}, {0.6, 0.25}, {0.3, 0.3}};  // weights of b and c
  std::vector<Vec<2>> xs;
  for (const auto& w : bary) xs.push_back(a + w[0] * (b - a) + w[1] * (c - a));
  auto p1 = [&](const Vec<2>& xa, const Vec<2>& x) {
    Mat<2> T;
    T << b - a, c - a;
    const Vec<2> w = T.inverse() * (x - a);
    if ((xa - a).norm() < 1e-9 * h) return 1.0 - w[0] - w[1];
    if ((xa - b).norm() < 1e-9 * h) return w[0];
    if ((xa - c).norm() < 1e-9 * h) return w[1];
    return 0.0;
  };
  double previous = 1.0;
  for (double gamma : {4.0, 8.0, 16.0, 32.0}) {
    const double e = distance_to_limit(nodes, h, gamma, xs, p1);
    std::printf("gamma %g  max |N_LME - N_P1| = %.3g\n", gamma, e);
    EXPECT_LT(e, previous) << "gamma " << gamma;
    previous = e;
  }
  EXPECT_LT(previous, 1e-9) << "gamma 32";
}

// The cell list against brute force: the same set within R, and the k nearest in order.
template <int D>
void check_search() {
  const auto nodes = grid_nodes<D>(D == 2 ? 20 : 8, 0.1, 0.45, 3);
  const NodeCellList<D> list(nodes, 0.25);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 2.8);  // some points outside the node box
  std::vector<NodeDistance> found;
  for (int k = 0; k < 50; ++k) {
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = u(rng);
    std::vector<NodeDistance> all;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      all.push_back({static_cast<std::int32_t>(i), (nodes[i] - x).norm()});
    std::sort(all.begin(), all.end());
    found.clear();
    list.within(x, 0.25, found);
    std::sort(found.begin(), found.end());
    std::size_t inside = 0;
    while (inside < all.size() && all[inside].distance < 0.25) ++inside;
    ASSERT_EQ(found.size(), inside) << "point " << k;
    for (std::size_t i = 0; i < inside; ++i) EXPECT_EQ(found[i].node, all[i].node);
    for (std::size_t n : {1u, 6u, 30u}) {
      list.nearest(x, n, found);
      ASSERT_EQ(found.size(), n);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(found[i].node, all[i].node) << "nearest " << n;
    }
  }
}

TEST(MeshfreeSearch, CellListMatchesBruteForce2D) { check_search<2>(); }
TEST(MeshfreeSearch, CellListMatchesBruteForce3D) { check_search<3>(); }

}  // namespace
