// MUSL (USL+) with the MLS velocity mapping (Gong 2015 §6.6): after the particles move, the new
// particle velocities are mapped back to the grid for the strain. Standard MUSL does it with the
// stencils and masses of the start of the step, so the MLS fit must use the start-of-step
// positions as well. A body in rigid rotation V = A X (A antisymmetric, no stress, no gravity)
// keeps its particle velocities in a FLIP step (no force), and MLS of degree 1 reproduces the
// linear field exactly where a node has enough particles around it: L = A, tr L = 0. A fit at
// the moved positions X + A X dt gives L = A - A^2 dt, tr L = 2 w^2 dt, a spurious dilatation.
#include <gtest/gtest.h>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

TEST(MlsMusl, RigidRotationGivesNoDilatation) {
  Spec spec = parse_spec(R"({
    "grid": {"dim": 2, "min": [0, 0], "max": [2, 2], "cell_size": 0.1},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e4, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.4, 0.4], "max": [1.6, 1.6]},
                "particles_per_cell": 3}],
    "solver": {"scheme": "musl", "transfer": "flip", "basis": "bspline2", "mapping": "mls_velocity",
               "dt": 1e-3, "end_time": 1}
  })");
  Simulation<2> sim = build_simulation<2>(spec);
  const double w = 1.0;
  const Vec<2> centre(1.0, 1.0);
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const Vec<2> r = sim.particles.x[p] - centre;
    sim.particles.v[p] = Vec<2>(-w * r[1], w * r[0]);
  }
  ExplicitStepper<2, TensorStencils<2, QuadraticBSplineBasis>> stepper(sim);
  stepper.step(1e-3);
  int interior = 0;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const Vec<2> x = sim.particles.x[p];
    if ((x - centre).cwiseAbs().maxCoeff() > 0.3) continue;  // 3 cells inside the body's edge
    ++interior;
    EXPECT_LT(std::abs(sim.particles.L[p].trace()), 1e-9 * w) << "particle " << p;  // old: 2 w^2 dt = 2e-3
    EXPECT_NEAR(sim.particles.L[p](1, 0), w, 1e-9);
  }
  EXPECT_GT(interior, 100);
}

}  // namespace
