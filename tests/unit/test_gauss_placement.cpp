// bodies[].placement "gauss" on a square grid (particles/generators.cpp): with particles_per_cell n = 2
// or 3 the particles are the n-point Gauss-Legendre rule of every cell, each with its weight's share
// of the cell's volume. Gauss-Legendre with n points is exact for polynomials of degree 2n - 1 in
// each direction, so the particle sums V_p x^i y^j over the box [0, 2] x [0, 0.75] must equal the
// exact integrals for i, j <= 2n - 1 (and miss x^{2n}: the rule is not the sub-cell midpoint rule).
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/particles/generators.hpp"

namespace {

using namespace matpoint;

double particle_moment(const ParticleSet<2>& particles, int i, int j) {
  double sum = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p)
    sum += particles.volume0[p] * std::pow(particles.x[p][0], i) * std::pow(particles.x[p][1], j);
  return sum;
}

double exact_moment(int i, int j) {  // over [0, 2] x [0, 0.75]
  return std::pow(2.0, i + 1) / (i + 1) * std::pow(0.75, j + 1) / (j + 1);
}

TEST(GaussPlacement, IsTheGaussLegendreRuleOfEveryCell) {
  for (int n : {2, 3}) {
    SCOPED_TRACE(n);
    Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.25), {4, 3}, 1);
    BodySpec body;
    body.shape = BodyShape::Box;
    body.min = {0.0, 0.0, 0.0};
    body.max = {2.0, 0.75, 0.0};
    body.particles_per_cell = n;
    body.gauss_points = true;
    MaterialSpec material;
    material.density = 2.0;
    ParticleSet<2> particles;
    ASSERT_EQ(generate_body<2>(body, 0, material, grid, particles), static_cast<std::size_t>(12 * n * n));
    for (int i = 0; i <= 2 * n - 1; ++i)
      for (int j = 0; j <= 2 * n - 1; ++j)
        EXPECT_NEAR(particle_moment(particles, i, j), exact_moment(i, j), 1e-12 * exact_moment(i, j))
            << "x^" << i << " y^" << j;
    EXPECT_GT(std::abs(particle_moment(particles, 2 * n, 0) - exact_moment(2 * n, 0)), 1e-6);
    double mass = 0.0;
    for (double m : particles.mass) mass += m;
    EXPECT_NEAR(mass, 2.0 * 2.0 * 0.75, 1e-12);
  }
}

}  // namespace
