// Threads: the same input gives bitwise the same particles on one, two and three threads. Every
// particle-to-grid sum visits the particles in the stencils' brick order (grid/brick_schedule.hpp),
// so each node adds its terms in one order whatever the thread count (docs/scale-out.md §6). Before
// the brick order, one and two threads differed by 5e-9 in the velocities of a two-disks run after
// the impact (the thread bands regrouped the boundary sums).
#include <gtest/gtest.h>
#include <omp.h>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;

template <class Stencils = TensorStencils<2, QuadraticBSplineBasis>>
ParticleSet<2> run_two_disks(int threads, ShapeKind shape = ShapeKind::BSpline2) {
  Spec spec = test::load_example("two-disks");
  spec.solver.shape = shape;
  spec.grid.cell_size = {0.01, 0.01, 0};  // ~10 000 particles: above the single-thread threshold
  spec.grid.cells = {100, 100, 0};
  spec.bodies[0].velocity = {0.5, 0.5, 0};  // make them meet within the steps below
  spec.bodies[1].velocity = {-0.5, -0.5, 0};
  spec.bodies[0].center = {0.35, 0.35, 0};
  spec.bodies[1].center = {0.65, 0.65, 0};
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto sim = build_simulation<2>(spec);
  ExplicitStepper<2, Stencils> stepper(sim);
  for (int k = 0; k < 60; ++k) stepper.step(1e-3);
  omp_set_num_threads(saved);
  EXPECT_GT(sim.particles.size(), 2u * kParallelMinimum);
  return sim.particles;
}

template <class Stencils = TensorStencils<2, QuadraticBSplineBasis>>
void check_threads_agree(ShapeKind shape = ShapeKind::BSpline2) {
  const auto one = run_two_disks<Stencils>(1, shape);
  double smax = 0;
  for (std::size_t p = 0; p < one.size(); ++p) smax = std::max(smax, one.stress[p].norm());
  EXPECT_GT(smax, 1.0) << "the disks must have collided for the test to mean something";
  for (const int threads : {2, 3}) {
    const auto other = run_two_disks<Stencils>(threads, shape);
    ASSERT_EQ(one.size(), other.size());
    std::size_t differ = 0;
    for (std::size_t p = 0; p < one.size(); ++p) {
      ASSERT_EQ(one.id[p], other.id[p]);
      if (one.x[p] != other.x[p] || one.v[p] != other.v[p] || one.stress[p] != other.stress[p]) ++differ;
    }
    EXPECT_EQ(differ, 0u) << threads << " threads: particles whose position, velocity or stress differ "
                          << "in any bit from the one-thread run";
  }
}

TEST(Threads, OneTwoAndThreeThreadsAgreeBitwise) { check_threads_agree(); }

/// The domain bases: per-particle half-widths (B2GIMP) and per-particle node boxes with tracked
/// corners (CPDI2) go through the same brick order (their bricks from the node box's lowest node).
TEST(Threads, OneTwoAndThreeThreadsAgreeBitwiseWithDomainBases) {
  check_threads_agree<TensorStencils<2, B2GimpBasis>>(ShapeKind::B2GIMP);
  check_threads_agree<CpdiStencils<2, HatKernel, CpdiDomain::Tracked>>(ShapeKind::CPDI2);
}

}  // namespace
