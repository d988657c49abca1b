// FE bodies on their own (Aulisa & Capodaglio §4, eqs. (36)-(43), (46); fem/fe_body.hpp): the FE side
// of the MPM-FEM coupling verified before it is coupled.
//  1. The static cantilever of Iaconeta 2017 §5.1 (examples/cantilever-static: l = 8 m, 1 x 1 m,
//     E = 90 MPa, nu = 0, rho = 1000, g = 9.81, one load step) as an FE body of Q4 elements with
//     2 x 2 Gauss points: its free-end mid-height node must reproduce the total-Lagrangian Q4 FEM
//     computation written for this project from the paper's data (-0.599659, -0.653912, -0.669125 m
//     for h = 0.5, 0.25, 0.125; tests/verification/test_cantilever_static.cpp) to 1e-4 relative, and
//     the geometrically linear variant its linear column (-0.602261, -0.657265, -0.672711,
//     -0.676693 m), whose Richardson limit must lie within 2e-4 m of Timoshenko's 0.67806 m
//     (Iaconeta 2017 eq. (62); beam theory's own error is 1.3e-4 m there).
//  2. Dynamics (nodal Newmark, eq. (46)): a bar fixed at x = 0 under a suddenly applied uniform axial
//     body force g (plane strain, nu = 0, so that it is a 1-D bar; small strain). The continuum tip
//     displacement is u(L, t) = sum_n a_n (1 - cos w_n t) with only odd modes w_n = (2n - 1) pi c /
//     (2L): it reaches exactly 2 u_s = rho g L^2 / E at t = 2L / c, when every mode is at its crest.
//     With the average-acceleration Newmark (beta = 1/4, gamma = 1/2) on the linear system, started
//     from the consistent a^0 = g (solver.implicit.initial_acceleration "body_force", extraction A17),
//     the discrete energy K + U - f . u is conserved exactly: checked to 1e-9 of f . u_s. The run's
//     own account of gravity's work on the body (history.csv's external_work) equals f . u to
//     round-off.
//     The tip's first crest must come at t = 2L/c and reach 2 u_s, each within 1e-3 (40 elements,
//     dt = T/400; the discrete fundamental's own errors, (kh)^2/24 in space and (w dt)^2/12 in
//     time, are below 1e-4; the rest is the higher modes' phases and the crest fit).
//  3. The compatibility inertia of the authors' code (extraction A2, "inertia": "unit_density"):
//     the same bar with unit inertia density vibrates sqrt(rho) times faster.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/mesh/structured_mesh.hpp"
#include "matpoint/run/runner.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace {

/// The cantilever example with its particles replaced by one FE body over the whole mesh, solved by
/// the particle-Newmark formulation's static analysis.
Spec fe_cantilever_spec(int nx, int ny, double h, bool small) {
  Spec spec = test::load_example("cantilever-static");
  spec.solver.kind = SolverKind::ImplicitMpm;
  spec.solver.implicit.small_strain = small;
  spec.bodies.clear();
  FeBodySpec beam;
  beam.name = "beam";
  beam.region_min = {-1, -1, 0};
  beam.region_max = {9, 2, 0};
  spec.fe_bodies = {beam};
  spec.mesh.cells = {nx, ny, 1};
  spec.grid.cells = {nx, ny, 1};
  spec.grid.cell_size = {h, h, 1.0};
  return spec;
}

Index node_at(const mesh::Mesh<2>& m, const Vec<2>& x) {
  for (Index n = 0; n < m.node_count(); ++n)
    if ((m.nodes[static_cast<std::size_t>(n)] - x).norm() < 1e-9) return n;
  ADD_FAILURE() << "no node at (" << x[0] << ", " << x[1] << ")";
  return 0;
}

double fe_point_a_deflection(double h, bool small) {
  const int nx = static_cast<int>(std::lround(8.0 / h)), ny = static_cast<int>(std::lround(1.0 / h));
  const Spec spec = fe_cantilever_spec(nx, ny, h, small);
  mesh::Mesh<2> m = mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 8, nx),
                                               mesh::AxisSpacing::uniform(0, 1, ny));
  implicit::ImplicitMpmSolver<mesh::Q4> solver(spec, m);
  EXPECT_EQ(solver.sim().particles.size(), 0u);
  EXPECT_EQ(solver.fe_bodies_state().element_count(), nx * ny);
  solver.step(1.0);
  const Index a = node_at(solver.mesh(), Vec<2>(8.0, 0.5));
  const double uy = solver.fe_bodies_state().displacement[static_cast<std::size_t>(a)][1];
  std::printf("FE cantilever h = %g%s: Point A u_y = %.6f m (%ld Newton iterations)\n", h,
              small ? " (small)" : "", uy, solver.totals().newton_iterations);
  return uy;
}

TEST(FeBody, StaticCantileverMatchesTheQ4Fem) {
  const double h[] = {0.5, 0.25, 0.125};
  const double fem[] = {-0.599659, -0.653912, -0.669125};
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(fe_point_a_deflection(h[k], false), fem[k], 1e-4 * std::abs(fem[k]));
}

TEST(FeBody, SmallStrainCantileverConvergesToTimoshenko) {
  const double h[] = {0.125, 0.0625};
  const double fem[] = {-0.672711, -0.676693};
  double u[2];
  for (int k = 0; k < 2; ++k) {
    u[k] = fe_point_a_deflection(h[k], true);
    EXPECT_NEAR(u[k], fem[k], 1e-4 * std::abs(fem[k]));
  }
  const double extrapolated = -(u[1] + (u[1] - u[0]) / 3.0);
  EXPECT_NEAR(extrapolated, 0.67806, 2e-4);
}

/// The bar of item 2: L = 1 m, 1 x 0.05 m, E = 1e6 Pa, nu = 0, rho (or unit inertia density),
/// fixed at x = 0, axial body force g = 10 m/s^2 from t = 0; `cells` along x, dt = T / steps_per_period.
struct BarRun {
  std::vector<double> time, tip;   // tip displacement after each step
  double max_energy_error = 0.0;   // |E_n - E_0| / (f . u_s) over the run, E = K + U - f . u
  double max_work_mismatch = 0.0;  // |W_ext - f . u| / (f . u_s): the run's gravity work on the body
  double u_static = 0.0, half_period = 0.0;
  double crest_time = 0.0,
         crest = 0.0;  // the first maximum of the tip (a parabola through the top 3 samples)
};

BarRun run_bar(int cells, int steps_per_period, double periods, bool unit_inertia) {
  const double L = 1.0, E = 1e6, rho = 100.0, g = 10.0;
  Spec spec = test::load_example("cantilever-static");
  spec.solver.kind = SolverKind::ImplicitMpm;
  spec.solver.implicit.static_analysis = false;
  spec.solver.implicit.small_strain = true;
  spec.solver.implicit.beta = 0.25;
  spec.solver.implicit.gamma = 0.5;
  spec.solver.implicit.initial_acceleration_from_body_force = true;
  spec.materials[0].density = rho;
  spec.materials[0].youngs_modulus = E;
  spec.materials[0].lambda = 0.0;
  spec.materials[0].mu = E / 2.0;
  spec.loads.gravity = {g, 0, 0};
  spec.bodies.clear();
  FeBodySpec bar;
  bar.name = "bar";
  bar.region_min = {-1, -1, 0};
  bar.region_max = {2, 1, 0};
  bar.unit_inertia_density = unit_inertia;
  spec.fe_bodies = {bar};
  spec.mesh.min = {0, 0, 0};
  spec.mesh.max = {L, 0.05, 0};
  spec.mesh.cells = {cells, 1, 1};
  spec.grid.min = spec.mesh.min;
  spec.grid.max = spec.mesh.max;
  spec.grid.cells = {cells, 1, 1};
  spec.grid.cell_size = {L / cells, 0.05, 1.0};
  mesh::Mesh<2> m =
      mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, L, cells),
                                 mesh::AxisSpacing::uniform(0, 0.05, 1));
  implicit::ImplicitMpmSolver<mesh::Q4> solver(spec, m);
  const double c = std::sqrt(E / (unit_inertia ? 1.0 : rho));
  BarRun out;
  out.half_period = 2.0 * L / c;
  out.u_static = rho * g * L * L / (2.0 * E);
  const double dt = 2.0 * out.half_period / steps_per_period;
  const Index tip = node_at(solver.mesh(), Vec<2>(L, 0.0));
  const auto& fe = solver.fe_bodies_state();
  const double load_scale = rho * g * L * 0.05 * out.u_static;  // f . u_s: the energy scale
  const auto steps = static_cast<int>(std::lround(periods * steps_per_period));
  for (int s = 0; s < steps; ++s) {
    solver.step(dt);
    out.time.push_back((s + 1) * dt);
    out.tip.push_back(fe.displacement[static_cast<std::size_t>(tip)][0]);
    // K + U - f . u: the kinetic and strain columns of history.csv, and the load's potential
    const auto row = solver.history_values();
    const auto columns = solver.history_columns();  // the FE body's columns, by name
    const auto column = [&](const std::string& suffix) {
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c].ends_with(suffix)) return row.at(c);
      ADD_FAILURE() << "no history column *" << suffix;
      return 0.0;
    };
    const double kinetic = column("_kinetic_energy"), strain = column("_strain_energy");
    double potential = 0.0;  // - sum_g m_g g . u(x_g), the gravity (per unit mass) on rho V0 always
    const auto& rule = fem::fe_gauss_rule<mesh::Q4>();
    for (Index k = 0; k < fe.element_count(); ++k) {
      const auto nodes = solver.mesh().element_nodes(fe.mesh_element(k));
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const auto N = mesh::Q4::values(rule.points[q]);
        double ux = 0.0;
        for (int I = 0; I < 4; ++I)
          ux += N[I] * fe.displacement[static_cast<std::size_t>(nodes[static_cast<std::size_t>(I)])][0];
        potential -= rho * fe.volume0[static_cast<std::size_t>(k) * rule.points.size() + q] * g * ux;
      }
    }
    out.max_energy_error =
        std::max(out.max_energy_error, std::abs(kinetic + strain + potential) / load_scale);
    // history.csv's totals (other_bodies_energy): the work summed step by step equals f . u
    out.max_work_mismatch = std::max(
        out.max_work_mismatch, std::abs(solver.other_bodies_energy().external_work + potential) / load_scale);
  }
  for (std::size_t k = 1; k + 1 < out.tip.size(); ++k)
    if (out.tip[k] >= out.tip[k - 1] && out.tip[k] > out.tip[k + 1]) {
      const double a = out.tip[k - 1], b = out.tip[k], c2 = out.tip[k + 1];
      const double shift = 0.5 * (a - c2) / (a - 2 * b + c2);  // in steps, from sample k
      out.crest_time = out.time[k] + shift * dt;
      out.crest = b - 0.25 * (a - c2) * shift;
      break;
    }
  return out;
}

/// Tip displacement at time t, linear between steps.
double tip_at(const BarRun& run, double t) {
  for (std::size_t k = 1; k < run.time.size(); ++k)
    if (run.time[k] >= t) {
      const double w = (t - run.time[k - 1]) / (run.time[k] - run.time[k - 1]);
      return (1 - w) * run.tip[k - 1] + w * run.tip[k];
    }
  return run.tip.back();
}

TEST(FeBody, SuddenlyLoadedBarReachesTwiceTheStaticTipAtHalfAPeriod) {
  const BarRun bar = run_bar(40, 400, 0.75, false);
  std::printf(
      "bar: first crest at %.5f of 2L/c, %.5f of 2 u_s; tip(2L/c) = %.5f of 2 u_s; energy drift %.2e\n",
      bar.crest_time / bar.half_period, bar.crest / (2 * bar.u_static),
      tip_at(bar, bar.half_period) / (2 * bar.u_static), bar.max_energy_error);
  EXPECT_LT(bar.max_work_mismatch, 1e-12);
  EXPECT_NEAR(bar.crest_time / bar.half_period, 1.0, 1e-3);
  EXPECT_NEAR(bar.crest / (2 * bar.u_static), 1.0, 1e-3);
  EXPECT_LT(bar.max_energy_error, 1e-9);
}

TEST(FeBody, UnitInertiaDensityVibratesSqrtRhoFaster) {
  const BarRun physical = run_bar(20, 200, 0.5, false);
  const BarRun unit = run_bar(20, 200, 0.5, true);
  // The same discrete system with its mass matrix divided by rho: the same tip history in time scaled
  // by 1/sqrt(rho), step for step (dt scales with the period).
  ASSERT_EQ(physical.tip.size(), unit.tip.size());
  EXPECT_NEAR(unit.half_period * std::sqrt(100.0), physical.half_period, 1e-12);
  for (std::size_t k = 0; k < unit.tip.size(); ++k)
    EXPECT_NEAR(unit.tip[k], physical.tip[k], 1e-9 * physical.u_static);
}

#ifdef MATPOINT_TEST_INPUTS_DIR
// What only the implicit solver's set-up finds (the mesh is built there): an element set the mesh
// lacks, a region without elements, particles inside an FE body. `matpoint run` refuses them with
// exit 2 before writing anything; each file's first line names the JSON path, as in inputs/bad/.
TEST(FeBody, SetUpRefusesBadFeBodiesAtTheirPath) {
  const std::filesystem::path folder = std::filesystem::path(MATPOINT_TEST_INPUTS_DIR) / "bad_setup";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    ++count;
    SCOPED_TRACE(entry.path().filename().string());
    std::ifstream in(entry.path());
    std::string first;
    std::getline(in, first);
    const std::string path = first.substr(10, first.find(": ") - 10);  // "// expect PATH: ..."
    RunOptions options;
    options.out_dir = std::filesystem::temp_directory_path() / "matpoint_fe_bad_setup";
    options.progress = false;
    try {
      (void)run_explicit(load_spec(entry.path()), options);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      bool found = false;
      for (const auto& issue : e.issues()) found = found || issue.path == path;
      EXPECT_TRUE(found) << "expected an issue at " << path << ", got: " << e.what();
    }
  }
  EXPECT_EQ(count, 3);
}
#endif

}  // namespace
}  // namespace matpoint
