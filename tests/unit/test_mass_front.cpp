// final_runout_x of a run on several MPI ranks (run/run_loop.hpp mass_front_x): the smallest
// particle x with at least the given fraction of the mass at or behind it, found by bisection on the
// doubles with one sum of the mass behind each trial x over the ranks. Here on one rank, against
// values counted by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/run/run_loop.hpp"

namespace {

using namespace matpoint;

ParticleSet<2> row(const std::vector<double>& xs, const std::vector<double>& masses) {
  ParticleSet<2> ps;
  for (std::size_t k = 0; k < xs.size(); ++k)
    ps.add(Vec<2>(xs[k], 0.5), Vec<2>(0, 0), masses[k], 1.0, Vec<2>(1, 1), 0, 0);
  return ps;
}

TEST(MassFront, SmallestXWithTheFractionOfTheMassBehindIt) {
  // x = 9, 8, ..., 0 (unsorted storage), unit masses: 99 % of 10 needs all ten; 50 % five (x <= 4)
  std::vector<double> xs;
  for (int k = 9; k >= 0; --k) xs.push_back(k);
  const auto ps = row(xs, std::vector<double>(10, 1.0));
  const Communicator one;
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 0.99, one), 9.0);
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 0.5, one), 4.0);
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 0.51, one), 5.0);
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 0.05, one), 0.0);
  // a heavy particle carries the front: masses 1 at x = 0..8 and 91 at x = 9
  std::vector<double> masses(10, 1.0);
  masses[0] = 91.0;  // x = 9
  EXPECT_EQ(run_loop_detail::mass_front_x(row(xs, masses), 0.09, one), 8.0);
  EXPECT_EQ(run_loop_detail::mass_front_x(row(xs, masses), 0.10, one), 9.0);
}

TEST(MassFront, NegativeCoordinatesAndSignedZeros) {
  // -3, -0, +0, 2 with unit masses: half the mass lies at x <= 0 (three particles), a quarter at -3
  const auto ps = row({2.0, -0.0, 0.0, -3.0}, {1, 1, 1, 1});
  const Communicator one;
  const double half = run_loop_detail::mass_front_x(ps, 0.5, one);
  EXPECT_EQ(half, 0.0);
  EXPECT_FALSE(std::signbit(half));  // reported as +0
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 0.25, one), -3.0);
  EXPECT_EQ(run_loop_detail::mass_front_x(ps, 1.0, one), 2.0);
  EXPECT_TRUE(std::isnan(run_loop_detail::mass_front_x(ParticleSet<2>{}, 0.99, one)));  // no particle
}

}  // namespace
