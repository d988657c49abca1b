// Iaconeta et al. 2017 §5.1 with the Galerkin meshfree method (§4.2): the static cantilever under
// self-weight (l = 8 m, 1 x 1 m section, E = 90 MPa, nu = 0, rho = 1000, g = 9.81, the compressible
// neo-Hookean of §7.1) in one quasi-static load step. Nodes: the vertices of the h-mesh; material
// points: its 2 x 2 Gauss points (the paper's set-up; the mesh is then discarded). R = 2 sqrt(2) h,
// MLS R_eff = R / 2, LME gamma = 1.8 (extraction §6.4), the clamp by Lagrange multipliers on the
// field at the fixed nodes (extraction A14). Point A is the free end's mid-height (extraction A2),
// where the field sum_I N_I(x_A) u_I is evaluated. Expected (paper §5.1, Fig. 7): against the
// finest-mesh value 0.67433 m, all methods converge quadratically, the GMM-MLS error curve
// coincides with FEM's and MPM's, and GMM-LME's lies above it.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "matpoint/implicit/meshfree/meshfree_stepper.hpp"
#include "matpoint/material/neo_hookean.hpp"

namespace matpoint {
namespace gmm_cantilever_tests {

constexpr double kPaperReference = 0.67433;  // Iaconeta 2017 §5.1, finest mesh (h = 0.01)

implicit::MeshfreeBody<2> cantilever(double h) {
  const int nx = static_cast<int>(std::lround(8.0 / h)), ny = static_cast<int>(std::lround(1.0 / h));
  implicit::MeshfreeBody<2> body;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      body.node_x.emplace_back(i * h, j * h);
      body.fixed.push_back(i == 0), body.fixed.push_back(i == 0);
    }
  body.node_v.assign(body.node_x.size(), Vec<2>::Zero());
  body.node_a = body.node_v;
  const double g = 0.5 / std::sqrt(3.0);  // Gauss points at 1/2 -+ 1/(2 sqrt 3) of the cell
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (double sy : {-g, g})
        for (double sx : {-g, g}) {
          body.point_x.emplace_back((i + 0.5 + sx) * h, (j + 0.5 + sy) * h);
          body.point_volume0.push_back(0.25 * h * h);
          body.point_mass.push_back(1000.0 * 0.25 * h * h);
          body.point_F.push_back(Mat<2>::Identity());
        }
  return body;
}

/// Point A's vertical displacement with the given basis, spacing h and R / h (R_eff = R / 2), and
/// the MLS weight's form (shape/meshfree_mls.hpp).
double point_a_deflection(MeshfreeBasis basis, double h, double radius_factor,
                          MlsWeight weight = MlsWeight::Smooth) {
  implicit::MeshfreeStepOptions options;
  options.shape.basis = basis;
  options.shape.mls_weight = weight;
  options.shape.spacing = h;
  options.shape.radius_factor = radius_factor;
  options.shape.dilation_factor = radius_factor / 2;
  options.quasi_static = true;
  const NeoHookean material{1000.0, 0.0, 45e6};
  implicit::MeshfreeStepper<2, NeoHookean> stepper(material, options);
  auto body = cantilever(h);
  const auto nodes0 = body.node_x;
  const auto result = stepper.step(body, 1.0, Vec<2>(0.0, -9.81));
  EXPECT_TRUE(result.converged()) << result.message;
  MeshfreeStencils<2> a;
  build_meshfree_stencils<2>(std::vector<Vec<2>>{Vec<2>(8.0, 0.5)}, nodes0, options.shape, a);
  // Point A lies on the nodes' hull, where the LME Hessian is singular in the limit (the weak
  // Kronecker delta): flagged ill conditioned there, and the functions are the face's.
  EXPECT_TRUE(a.status[0] == MeshfreeStatus::Ok ||
              (basis == MeshfreeBasis::Lme && a.status[0] == MeshfreeStatus::IllConditioned));
  double uy = 0.0;
  for (auto k = a.offset[0]; k < a.offset[1]; ++k) uy += a.N[k] * stepper.last_increment()[2 * a.node[k] + 1];
  std::printf(
      "GMM-%s%s R = %.3g h, h = %g: Point A u_y = %.6f m, error %.3g (%d Newton iterations, %d colours)\n",
      basis == MeshfreeBasis::Mls ? "MLS" : "LME",
      basis == MeshfreeBasis::Mls ? (weight == MlsWeight::Smooth ? " (smooth)" : " (truncated)") : "",
      radius_factor, h, uy, std::abs(kPaperReference + uy), result.iterations(), stepper.colours());
  return uy;
}

constexpr double kH[] = {0.5, 0.25, 0.125};
// Total-Lagrangian Q4 FEM, 2 x 2 Gauss, same problem (extraction §8.1 [OURS], as in
// test_cantilever_static.cpp): Point A u_y = -0.599659, -0.653912, -0.669125 m.
constexpr double kFemError[] = {0.074671, 0.020418, 0.005205};

/// The hot loop's many colours (hundreds for clouds of 6-25 nodes) make threads wait more than
/// work on this test's small problems: one thread.
class GmmCantilever : public ::testing::Test {
 protected:
  void SetUp() override { saved_ = omp_get_max_threads(), omp_set_num_threads(1); }
  void TearDown() override { omp_set_num_threads(saved_); }
  int saved_ = 1;
};

// Reading A of the paper's "R = 2h2" (R = sqrt(2 h^2), the cell diagonal; R_eff = R / 2) with the
// authors' truncated Gaussian (extraction §6.2): Fig. 7's description holds. MLS's error curve coincides with
// FEM's (within a factor 1.5 at each h, on a log-log plot spanning two decades), LME's lies above MLS's, and
// both fall as h^2 (order 1.8-2.2 between the two finer meshes, the bound of the MPM test).
TEST_F(GmmCantilever, CellDiagonalRadiusReproducesFigure7) {
  double mls[3], lme[3];
  for (int k = 0; k < 3; ++k) {
    mls[k] = std::abs(kPaperReference +
                      point_a_deflection(MeshfreeBasis::Mls, kH[k], std::sqrt(2.0), MlsWeight::Truncated));
    lme[k] = std::abs(kPaperReference + point_a_deflection(MeshfreeBasis::Lme, kH[k], std::sqrt(2.0)));
    EXPECT_LT(mls[k], 1.5 * kFemError[k]) << "h = " << kH[k];
    EXPECT_GT(mls[k], kFemError[k] / 1.5) << "h = " << kH[k];
    EXPECT_GT(lme[k], mls[k]) << "h = " << kH[k];
  }
  for (const double* e : {mls, lme}) {
    const double order = std::log2(e[1] / e[2]);
    std::printf("order (h = 0.25 -> 0.125): %.2f\n", order);
    EXPECT_GE(order, 1.8);
    EXPECT_LE(order, 2.2);
  }
}

// Reading B (R = 2 sqrt(2) h, our default, extraction A5): the wider clouds are far more accurate
// than the Q4 FEM at every h (here the paper's "MLS = FEM" does not hold), and with LME and the
// truncated MLS weight the error falls.
TEST_F(GmmCantilever, TwiceTheCellDiagonalIsMoreAccurateThanFem) {
  for (auto [basis, weight] : {std::pair{MeshfreeBasis::Mls, MlsWeight::Truncated},
                               std::pair{MeshfreeBasis::Lme, MlsWeight::Smooth}}) {
    double previous = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double error =
          std::abs(kPaperReference + point_a_deflection(basis, kH[k], 2.0 * std::sqrt(2.0), weight));
      EXPECT_LT(error, kFemError[k]) << "h = " << kH[k];
      EXPECT_LT(error, previous) << "h = " << kH[k];
      previous = error;
    }
  }
}

// The smooth MLS weight (our default) at R = 2 sqrt(2) h: within 1e-3 of the reference already at
// h = 0.5 (measured 2e-4 to 4e-4, an order of magnitude below the Q4 FEM's error at h = 0.125), and
// converging: the change from h to h / 2 falls more than fourfold. Its values (about -0.6747 m) lie
// about 4e-4 beyond the reference, probably because the clamp holds the field at the fixed nodes
// only (a support a little softer than a clamped face); at these h that offset is larger than the
// error left, so the error against 0.67433 m does not fall (README.md of the example).
TEST_F(GmmCantilever, SmoothMlsWeightIsAccurateAndConverges) {
  double u[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = point_a_deflection(MeshfreeBasis::Mls, kH[k], 2.0 * std::sqrt(2.0), MlsWeight::Smooth);
    EXPECT_LT(std::abs(kPaperReference + u[k]), 1e-3) << "h = " << kH[k];
    EXPECT_LT(std::abs(kPaperReference + u[k]), kFemError[2]) << "h = " << kH[k];
  }
  EXPECT_LT(std::abs(u[2] - u[1]), std::abs(u[1] - u[0]) / 4);
}

}  // namespace gmm_cantilever_tests
}  // namespace matpoint
