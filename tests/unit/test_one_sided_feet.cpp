// The feet of implicit one-sided walls (implicit/one_sided_boundary.hpp): the particles near a body's
// surface carry the reference vector to its nearest point, so the wall meets the body's true surface.
//  - Disk of radius R: every foot lies on the circle (the bisection's 40 halvings: to 1e-9 R), and
//    the vector's length is the particle's distance to the circle, R - |X - c|, up to the angular
//    step of the search: at most 1/cos(2.5 deg) - 1 too long. Particles deeper than the search range
//    (1.5 times their size) have none; those within range cos(2.5 deg) of the surface all have one.
//  - The same disk resting on the floor y = 0: every candidate foot lies on the circle, its gap the
//    circle's height above the floor, R - sqrt(R^2 - (x_f - c_x)^2); the lowest foot touches (gap
//    below 1e-9 R), and along the bottom quarter of the circle neighbouring feet are closer than two
//    neighbouring search rays (5 deg apart) at the search range 1.5 s can be, 2 tan(2.5 deg) 1.5 s =
//    0.13 s (a fine polygon: a rigid disk on it rises by at most (0.13 s)^2 / (8 R)), while the
//    particles' domains put a flat row of them on the floor (the facet a rolling disk had to tip
//    over).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "matpoint/implicit/one_sided_boundary.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;

constexpr double kRadius = 0.2, kSpacing = 0.01;

/// Particles at the centres of a square lattice of cells kSpacing wide with a corner at the origin,
/// those inside the disk of radius kRadius about c.
ParticleSet<2> disk(const Vec<2>& c) {
  ParticleSet<2> particles;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) {
      const Vec<2> x = kSpacing * Vec<2>(i + 0.5, j + 0.5);
      if ((x - c).norm() <= kRadius)
        particles.add(x, Vec<2>::Zero(), 1.0, kSpacing * kSpacing, Vec<2>(kSpacing, kSpacing), 0, 0);
    }
  return particles;
}

BodyShapeTest<2> inside_disk(const Vec<2>& c) {
  return [c](int, const Vec<2>& x) { return (x - c).norm() <= kRadius; };
}

TEST(OneSidedFeet, FeetOfADiskLieOnItsCircleAtTheNearestPoint) {
  const Vec<2> c(0.5, 0.3);
  const ParticleSet<2> particles = disk(c);
  const auto r = nearest_surface_vectors<2>(particles, inside_disk(c));
  const double range = 1.5 * kSpacing, slack = 1.0 / std::cos(2.5 * M_PI / 180.0) - 1.0;
  int feet = 0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double depth = kRadius - (particles.x0[p] - c).norm();
    if (!std::isfinite(r[p][0])) {
      EXPECT_GT(depth, range * std::cos(2.5 * M_PI / 180.0)) << p;
      continue;
    }
    ++feet;
    EXPECT_NEAR((particles.x0[p] + r[p] - c).norm(), kRadius, 1e-9 * kRadius) << p;
    EXPECT_GE(r[p].norm(), depth - 1e-9 * kRadius) << p;
    EXPECT_LE(r[p].norm(), depth * (1.0 + slack) + 1e-9 * kRadius) << p;
  }
  EXPECT_GT(feet, 2 * M_PI * kRadius / kSpacing);  // at least one layer of feet around the circle
}

TEST(OneSidedFeet, ADiskOnTheFloorMeetsItWhereItsCircleDoes) {
  const Vec<2> c(0.505, kRadius);  // the circle touches y = 0 below a column of particles
  const ParticleSet<2> particles = disk(c);
  const OneSidedNode floor{0, WallPlane{1, 0.0, -1.0}, true};
  OneSidedBoundary<2> wall({floor}, 10, inside_disk(c));
  wall.start_step(particles, 1e-3);
  ASSERT_FALSE(wall.candidates().empty());
  double lowest = 1.0;
  for (std::size_t k = 0; k < wall.candidates().size(); ++k) {
    const auto& foot = wall.candidates()[k];
    const double dx = foot.foot[0] - c[0];
    EXPECT_NEAR(foot.gap, kRadius - std::sqrt(kRadius * kRadius - dx * dx), 1e-9 * kRadius) << k;
    lowest = std::min(lowest, foot.gap);
  }
  EXPECT_LT(lowest, 1e-9 * kRadius);
  std::vector<double> bottom;  // the feet's x along the bottom quarter of the circle
  for (const auto& foot : wall.candidates())
    if (std::abs(foot.foot[0] - c[0]) < 0.25 * kRadius) bottom.push_back(foot.foot[0]);
  std::sort(bottom.begin(), bottom.end());
  double widest = 0.0;
  for (std::size_t k = 1; k < bottom.size(); ++k) widest = std::max(widest, bottom[k] - bottom[k - 1]);
  EXPECT_LT(widest, 2.0 * std::tan(2.5 * M_PI / 180.0) * 1.5 * kSpacing);
  int domains_on_floor = 0;  // the particles' square domains reaching y = 0
  for (std::size_t p = 0; p < particles.size(); ++p)
    domains_on_floor += particles.x[p][1] - particles.half_extent(p, Vec<2>::UnitY()) <= 1e-12;
  EXPECT_GT(domains_on_floor, 3);
  std::printf(
      "widest gap between feet along the bottom: %.3g m (spacing %.3g m); particle domains on the floor: "
      "%d\n",
      widest, kSpacing, domains_on_floor);
}

// newmark_stop_displacement: the displacement over a step after which Newmark's velocity update
// (Iaconeta eq. (43)) gives v^(n+1) = 0, for the trapezoidal rule and two damped pairs; and u = 0
// instead reverses v under the trapezoidal rule (why a no-slip foot is held at the former).
TEST(OneSidedFeet, StopDisplacementEndsANewmarkStepAtRest) {
  const Vec<2> v(1.3, -0.4), a(-7.0, 2.5);
  const double dt = 2.5e-3;
  for (const auto& [beta, gamma] : {std::pair{0.25, 0.5}, std::pair{0.3025, 0.6}, std::pair{0.3, 0.5}}) {
    const auto v_end = [&](const Vec<2>& u) {
      return Vec<2>(gamma / (beta * dt) * u - (gamma / beta - 1.0) * v -
                    dt * (gamma / (2.0 * beta) - 1.0) * a);
    };
    EXPECT_LT(v_end(newmark_stop_displacement<2>(v, a, dt, beta, gamma)).norm(), 1e-12) << beta;
    if (beta == 0.25) {  // u = 0 reverses v (the trapezoidal rule's a^n term vanishes)
      EXPECT_LT((v_end(Vec<2>::Zero()) + v).norm(), 1e-12);
    }
  }
  // add_foot_penalty's tangential spring rests at the given displacement: two nodes with weights W,
  // sum_J W_J u_J equal to the rest value on the tangential axis gives no tangential force.
  const std::vector<double> W{0.3, 0.7};
  const double rest[2] = {0.004, 0.0};
  const double u[4] = {0.002, 0.0, (0.004 - 0.3 * 0.002) / 0.7, 0.0};
  double r[4] = {0, 0, 0, 0};
  add_foot_penalty<2>(W, /*normal_axis=*/1, /*outward=*/-1.0, /*gap=*/0.0, /*no_slip=*/true, 1e6, u, r,
                      nullptr, rest);
  EXPECT_NEAR(r[0], 0.0, 1e-9);
  EXPECT_NEAR(r[2], 0.0, 1e-9);
}

// The contact set's update after a solve (step 4 of one_sided_boundary.hpp): a free foot past the
// wall is held, a held foot whose spring the wall would stretch (pull) is released, a foot pushed on
// stays; a stretch or pass within the tolerance (1e-8 of the particle's size: the solve's accuracy)
// changes nothing. A set in which nothing pulls and nothing is past is settled (update: false).
TEST(OneSidedFeet, UpdateReleasesPullingFeetAndHoldsThoseThatPassedTheWall) {
  const double size = 0.1, tolerance = kContactTolerance * size;
  ParticleSet<2> particles;
  for (int i = 0; i < 4; ++i)  // touching the floor y = 0: held from the start
    particles.add(Vec<2>(i * size, 0.5 * size), Vec<2>::Zero(), 1.0, size * size, Vec<2>(size, size), 0, 0);
  for (int i = 4; i < 6; ++i)  // 0.05 above it
    particles.add(Vec<2>(i * size, 0.5 * size + 0.05), Vec<2>::Zero(), 1.0, size * size, Vec<2>(size, size),
                  0, 0);
  const WallPlane floor{1, 0.0, -1.0};
  OneSidedBoundary<2> wall({OneSidedNode{0, floor, true}});
  wall.start_step(particles, 1e-3);
  ASSERT_EQ(wall.candidates().size(), 6U);
  EXPECT_EQ(wall.in_contact(), (std::vector<char>{1, 1, 1, 1, 0, 0}));
  // Stretches gap + inward: 0.4 pulls, -0.2 is pushed on, 0.5 and -0.5 tolerances are round-off;
  // the free feet (gap 0.05) moved 0.1 and 0.05 + 0.5 tolerance towards the floor.
  const std::vector<double> inward{
      0.4, -0.2, 0.5 * tolerance, -0.5 * tolerance, -0.1, -0.05 - 0.5 * tolerance};
  EXPECT_TRUE(wall.update(inward));
  EXPECT_EQ(wall.in_contact(), (std::vector<char>{0, 1, 1, 1, 1, 0}));
  EXPECT_FALSE(wall.update(inward));  // settled
}

}  // namespace
