// CPDI2 moves its tracked corners and puts the particle at their centroid (Gong 2015 eqs.
// (6.28)-(6.29)); the corners must follow the run's position update, Nairn 2026 eqs. (7)-(9) with
// the position weight alpha, or FMPM's alpha = 1/2 would silently be alpha = 1. In a uniform
// motion under gravity every node has v+ = V + g dt and a = g, so every particle, corner and
// centroid moves by the formula's displacement exactly:
//   FLIP: dx = (v+ - (1 - alpha) a dt) dt,   PIC: dx = (alpha v+ + (1 - alpha) V) dt.
#include <gtest/gtest.h>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"

namespace {

using namespace matpoint;

struct Case {
  const char* transfer;
  double alpha;
};

class Cpdi2Motion : public ::testing::TestWithParam<Case> {};

TEST_P(Cpdi2Motion, CentroidFollowsTheTransfersPositionUpdate) {
  const Case c = GetParam();
  Spec spec = parse_spec(std::string(R"({
    "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e4, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3, 0.3], "max": [0.6, 0.7]},
                "particles_per_cell": 2, "velocity": [0.4, -0.3]}],
    "loads": {"gravity": [3, -10]},
    "solver": {"scheme": "usl", "basis": "cpdi2", "dt": 1e-3, "end_time": 1, "transfer": ")") +
                         c.transfer + R"(", "position_alpha": )" + std::to_string(c.alpha) + "}}");
  Simulation<2> sim = build_simulation<2>(spec);
  ExplicitStepper<2, CpdiStencils<2, HatKernel, CpdiDomain::Tracked>> stepper(sim);
  const auto x0 = sim.particles.x;
  const double dt = 1e-3;
  const Vec<2> V(0.4, -0.3), g(3.0, -10.0), v_plus = V + g * dt;
  const bool flip = std::string(c.transfer) == "flip";
  const Vec<2> dx = flip ? Vec<2>((v_plus - (1 - c.alpha) * g * dt) * dt)
                         : Vec<2>((c.alpha * v_plus + (1 - c.alpha) * V) * dt);
  stepper.step(dt);
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    EXPECT_LT((sim.particles.x[p] - x0[p] - dx).norm(), 1e-15) << "particle " << p;
}

INSTANTIATE_TEST_SUITE_P(TransfersAndAlpha, Cpdi2Motion,
                         ::testing::Values(Case{"flip", 1.0}, Case{"flip", 0.0}, Case{"flip", 0.5},
                                           Case{"pic", 0.5}, Case{"pic", 0.0}),
                         [](const auto& info) {
                           return std::string(info.param.transfer) + "_alpha" +
                                  std::to_string(static_cast<int>(info.param.alpha * 10));
                         });

}  // namespace
