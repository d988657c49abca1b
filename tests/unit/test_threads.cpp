// Threads: the same input gives the same result on one and two threads, to round-off (the
// scatter sums thread bands in a fixed order; only reductions of diagnostics regroup sums), and
// bitwise the same result when run twice on the same thread count.
#include "test_support.hpp"

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

#include <gtest/gtest.h>
#include <omp.h>

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
  const auto two = run_two_disks<Stencils>(2, shape);
  const auto again = run_two_disks<Stencils>(2, shape);
  ASSERT_EQ(one.size(), two.size());
  double dx = 0, dv = 0, ds = 0, smax = 0;
  for (std::size_t p = 0; p < one.size(); ++p) {
    ASSERT_EQ(one.id[p], two.id[p]);
    dx = std::max(dx, (one.x[p] - two.x[p]).norm());
    dv = std::max(dv, (one.v[p] - two.v[p]).norm());
    ds = std::max(ds, (one.stress[p] - two.stress[p]).norm());
    smax = std::max(smax, one.stress[p].norm());
    EXPECT_EQ(two.x[p], again.x[p]) << "same thread count must be bitwise reproducible";
    EXPECT_EQ(two.stress[p], again.stress[p]);
  }
  EXPECT_GT(smax, 1.0) << "the disks must have collided for the test to mean something";
  EXPECT_LT(dx, 1e-13);
  EXPECT_LT(dv, 1e-12);
  EXPECT_LT(ds, 1e-10 * smax);
}

TEST(Threads, OneAndTwoThreadsAgreeToRoundOff) { check_threads_agree(); }

/// The domain bases: per-particle half-widths (B2GIMP) and per-particle node boxes with tracked
/// corners (CPDI2) go through the same banded scatter (Stencils::node_span).
TEST(Threads, OneAndTwoThreadsAgreeWithDomainBases) {
  check_threads_agree<TensorStencils<2, B2GimpBasis>>(ShapeKind::B2GIMP);
  check_threads_agree<CpdiStencils<2, HatKernel, CpdiDomain::Tracked>>(ShapeKind::CPDI2);
}

}  // namespace
