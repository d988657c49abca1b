// The cloud repairs of Iaconeta et al. 2017 §5.3 (extraction §6.5): a variable radius with a
// minimum node count for MLS, and node augmentation for LME when Newton fails or the Hessian is
// ill conditioned. Each test builds a cloud that fails without the repair, checks the counters
// against a count made by brute force, and checks that the repaired functions satisfy eqs. (57).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <vector>

#include "matpoint/shape/meshfree_stencils.hpp"

namespace {

using namespace matpoint;

/// Nodes of a regular grid on [0, 1]^2 with spacing h, less those for which `drop` holds.
template <class Drop>
std::vector<Vec<2>> grid_without(double h, Drop&& drop) {
  std::vector<Vec<2>> nodes;
  const int n = static_cast<int>(std::lround(1.0 / h));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (const Vec<2> x(i * h, j * h); !drop(x)) nodes.push_back(x);
  return nodes;
}

/// Eqs. (57)-(58) for point p of the stencils.
void expect_consistent(const MeshfreeStencils<2>& s, std::size_t p, const Vec<2>& x,
                       const std::vector<Vec<2>>& nodes) {
  double sum = 0.0;
  Vec<2> reproduced = Vec<2>::Zero(), sum_grad = Vec<2>::Zero();
  Mat<2> grad_x = Mat<2>::Zero();
  for (auto k = s.offset[p]; k < s.offset[p + 1]; ++k) {
    sum += s.N[k];
    reproduced += s.N[k] * nodes[s.node[k]];
    sum_grad += s.dN[k];
    grad_x += nodes[s.node[k]] * s.dN[k].transpose();
  }
  EXPECT_NEAR(sum, 1.0, 1e-12) << "point " << p;
  EXPECT_LT((reproduced - x).norm(), 1e-12) << "point " << p;
  EXPECT_LT(sum_grad.norm(), 1e-9) << "point " << p;  // h = 0.1: 1e-10 / h
  EXPECT_LT((grad_x - Mat<2>::Identity()).norm(), 1e-10) << "point " << p;
}

std::size_t brute_force_count(const Vec<2>& x, const std::vector<Vec<2>>& nodes, double R) {
  std::size_t n = 0;
  for (const auto& y : nodes) n += (y - x).norm() < R;
  return n;
}

// A hole of radius 3.5 h around (0.5, 0.5): the point at its centre has no node within
// R = 2 sqrt(2) h (and one off centre only a few); with min_nodes = 6 its radius grows until it
// holds 6, and the functions are complete again. Points away from the hole are untouched. With the
// smooth weight the radius grows where fewer than 6 nodes lie within R / 1.25 (to 1.25 times the
// 6th node's distance, so that node keeps weight: meshfree_stencils.hpp); with the truncated one
// where fewer than 6 lie within R.
void check_variable_radius(MlsWeight form) {
  const double h = 0.1;
  const Vec<2> centre(0.5, 0.5);
  const auto nodes = grid_without(h, [&](const Vec<2>& x) { return (x - centre).norm() < 3.5 * h; });
  const std::vector<Vec<2>> points{centre, centre + Vec<2>(0.12, 0.0), {0.15, 0.15}, {0.85, 0.2}};
  MeshfreeParameters par;
  par.spacing = h;
  par.mls_weight = form;
  const double reach = form == MlsWeight::Smooth ? par.radius() / 1.25 : par.radius();
  std::int64_t sparse = 0;  // points with fewer than 6 nodes within the reach, counted by brute force
  for (const auto& x : points) sparse += brute_force_count(x, nodes, reach) < 6;
  ASSERT_EQ(sparse, 2);

  MeshfreeStencils<2> off;
  build_meshfree_stencils<2>(points, nodes, par, off);
  EXPECT_EQ(off.status[0], MeshfreeStatus::Empty);
  EXPECT_EQ(off.repairs.mls_radius_grown, 0);

  par.min_nodes = 6;
  MeshfreeStencils<2> on;
  build_meshfree_stencils<2>(points, nodes, par, on);
  EXPECT_EQ(on.repairs.mls_radius_grown, sparse);
  EXPECT_EQ(on.repairs.failed, 0);
  for (std::size_t p = 0; p < points.size(); ++p) {
    EXPECT_EQ(on.status[p], MeshfreeStatus::Ok) << p;
    EXPECT_GE(on.offset[p + 1] - on.offset[p], 6) << p;
    expect_consistent(on, p, points[p], nodes);
  }
}

TEST(MeshfreeRepairs, MlsVariableRadiusReachesTheMinimumNodeCount) {
  check_variable_radius(MlsWeight::Smooth);
}
TEST(MeshfreeRepairs, MlsVariableRadiusWithTheTruncatedWeight) {
  check_variable_radius(MlsWeight::Truncated);
}

// Nodes left of x = 0.5 removed within 3.5 h of x_p = (0.47, 0.5): the nodes within R all have
// x >= 0.5, so x_p lies outside their convex hull and Newton on the dual cannot converge (eq. (61)
// needs x in conv X). Adding the next-closest nodes (at >= 3.5 h, on the left) restores it.
TEST(MeshfreeRepairs, LmeAugmentationRecoversAPointOutsideTheCloudHull) {
  const double h = 0.1;
  const Vec<2> xp(0.47, 0.5);
  const auto nodes =
      grid_without(h, [&](const Vec<2>& x) { return (x - xp).norm() < 3.5 * h && x[0] < 0.5 - 1e-9; });
  MeshfreeParameters par;
  par.basis = MeshfreeBasis::Lme;
  par.spacing = h;
  const std::vector<Vec<2>> points{xp, {0.2, 0.8}};
  MeshfreeStencils<2> off;
  build_meshfree_stencils<2>(points, nodes, par, off);
  EXPECT_EQ(off.status[0], MeshfreeStatus::NotConverged);
  EXPECT_EQ(off.status[1], MeshfreeStatus::Ok);
  EXPECT_EQ(off.repairs.failed, 1);

  par.lme_max_nodes = 30;
  MeshfreeStencils<2> on;
  build_meshfree_stencils<2>(points, nodes, par, on);
  EXPECT_EQ(on.status[0], MeshfreeStatus::Ok);
  EXPECT_EQ(on.repairs.lme_augmented, 1);
  EXPECT_GE(on.repairs.lme_nodes_added, 1);
  EXPECT_EQ(on.repairs.failed, 0);
  EXPECT_EQ(static_cast<std::size_t>(on.offset[1]), brute_force_count(xp, nodes, par.radius()) +
                                                        static_cast<std::size_t>(on.repairs.lme_nodes_added));
  expect_consistent(on, 0, xp, nodes);
  expect_consistent(on, 1, points[1], nodes);
}

// x_p at distance delta = 1e-12 h inside the hull's face x = 0.5: Newton converges, but the
// Hessian's normal variance is ~ delta h, so 1 / cond(J) ~ delta / h falls far below 1e-9 and the
// point is flagged; augmentation with the nodes behind the face repairs it.
TEST(MeshfreeRepairs, LmeAugmentationRepairsAnIllConditionedHessian) {
  const double h = 0.1;
  const Vec<2> xp(0.5 + 1e-12 * h, 0.5);
  const auto nodes =
      grid_without(h, [&](const Vec<2>& x) { return (x - xp).norm() < 3.5 * h && x[0] < 0.5 - 1e-9; });
  MeshfreeParameters par;
  par.basis = MeshfreeBasis::Lme;
  par.spacing = h;
  MeshfreeStencils<2> off;
  build_meshfree_stencils<2>(std::vector<Vec<2>>{xp}, nodes, par, off);
  EXPECT_EQ(off.status[0], MeshfreeStatus::IllConditioned);

  par.lme_max_nodes = 30;
  MeshfreeStencils<2> on;
  build_meshfree_stencils<2>(std::vector<Vec<2>>{xp}, nodes, par, on);
  EXPECT_EQ(on.status[0], MeshfreeStatus::Ok);
  EXPECT_EQ(on.repairs.lme_augmented, 1);
  expect_consistent(on, 0, xp, nodes);
}

// The points are split among threads and joined in order: one and two threads give the same
// stencils bit for bit (LME with the augmentation on, over a jittered cloud with a hole).
TEST(MeshfreeStencils, ThreadCountDoesNotChangeTheResult) {
  const double h = 0.02;
  const Vec<2> centre(0.5, 0.5);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto nodes = grid_without(h, [&](const Vec<2>& x) { return (x - centre).norm() < 3.5 * h; });
  std::vector<Vec<2>> points;
  while (points.size() < 5000)
    if (const Vec<2> x(u(rng), u(rng)); (x - centre).norm() > 2 * h) points.push_back(x);
  MeshfreeParameters par;
  par.basis = MeshfreeBasis::Lme;
  par.spacing = h;
  par.lme_max_nodes = 30;
  const int saved = omp_get_max_threads();
  MeshfreeStencils<2> one, two;
  omp_set_num_threads(1);
  build_meshfree_stencils<2>(points, nodes, par, one);
  omp_set_num_threads(2);
  build_meshfree_stencils<2>(points, nodes, par, two);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.offset, two.offset);
  EXPECT_EQ(one.node, two.node);
  EXPECT_EQ(one.N, two.N);
  EXPECT_EQ(one.status, two.status);
  EXPECT_GT(one.repairs.lme_augmented, 0);  // points in the hole need it
  EXPECT_EQ(one.repairs.lme_augmented, two.repairs.lme_augmented);
  EXPECT_EQ(one.repairs.failed, two.repairs.failed);
  for (std::size_t k = 0; k < one.dN.size(); ++k) ASSERT_EQ(one.dN[k], two.dN[k]) << k;
}

}  // namespace
