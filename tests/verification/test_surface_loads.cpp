// loads.tractions through the implicit solver, on blocks whose exact solution is a uniform stress
// (which Q4 and Hex8 elements with particles at their Gauss points represent exactly):
//   - a dead traction t_y = -p on the top of a plane-strain block between smooth walls, small
//     strain, applied in 4 static load steps: sigma_yy = -p, sigma_xx = 0 at every particle, and the
//     external work of the ramp equals p w |v_top| / 2 (linear response; the trapezoidal sum of
//     the load's work is exact for it);
//   - a follower pressure p = 0.1 E on a neo-Hookean block in one static step (finite strain): the
//     Cauchy stress is sigma_yy = -p on the deformed (widened) top, sigma_xx = 0;
//   - the same in 3-D on Hex8 elements (pressure on the "front" face z = max): sigma_zz = -p.
// These fix the sign (pushing into the body), the face orientation of every side used, the
// follower's current area and the work bookkeeping; the thick cylinder (test_thick_cylinder.cpp)
// checks a non-uniform load path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace matpoint {
namespace {

constexpr double kYoung = 1e6, kPoisson = 0.3;

template <class E>
void run(implicit::ImplicitMpmSolver<E>& solver, const Spec& spec) {
  while (solver.sim().time < spec.solver.end_time - 1e-9) solver.step(solver.time_step());
}

/// A 2 x 1 plane-strain block between smooth walls (bottom, left) under t_y = -p on its top, ramped
/// linearly from 0 at t = 0 to p at t = 1, small strain, in `steps` static steps.
Spec dead_traction_spec(int steps) {
  return parse_spec(R"({
    "title": "dead traction on a block",
    "mesh": {"element": "q4", "min": [0, 0], "max": [2, 1], "cells": [4, 2]},
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 1e6, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0, 0], "max": [2, 1]},
                "placement": "gauss", "particles_per_cell": 2}],
    "boundary_conditions": [{"type": "slip", "boundary": "bottom", "normal": "y"},
                            {"type": "slip", "boundary": "left", "normal": "x"}],
    "loads": {"tractions": [{"boundary": "top", "traction": [0, {"table": [[0, 0], [1, -1000]]}]}]},
    "solver": {"type": "implicit_ul", "dt": )" +
                    std::to_string(1.0 / steps) + R"(, "end_time": 1,
               "implicit": {"analysis": "static", "kinematics": "small"}},
    "output": {"every_time": 100}
  })");
}

TEST(SurfaceLoads, DeadTractionGivesUniformStressAndItsWork) {
  const double p = 1e3;
  // One step from the undeformed mesh: the particles sit at the Gauss points, Q4 is exact.
  const Spec spec = dead_traction_spec(1);
  const auto rectangle = [] {
    return mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 2, 4),
                                      mesh::AxisSpacing::uniform(0, 1, 2));
  };
  implicit::ImplicitMpmSolver<mesh::Q4> solver(spec, rectangle());
  run(solver, spec);
  const auto& particles = solver.sim().particles;
  for (std::size_t q = 0; q < particles.size(); ++q) {
    EXPECT_NEAR(particles.stress[q](1, 1), -p, 1e-9 * p);
    EXPECT_NEAR(particles.stress[q](0, 0), 0.0, 1e-9 * p);
  }
  // Plane strain, sigma_xx = 0: eps_yy = -p (1 - nu^2) / E; the top moves by eps_yy over the height 1.
  const double top_displacement = p * (1 - kPoisson * kPoisson) / kYoung;
  EXPECT_NEAR(particles.F[0](1, 1) - 1, -top_displacement, 1e-9 * top_displacement);
  const double work = 0.5 * p * 2.0 * top_displacement;  // width 2; the load grows with the displacement
  EXPECT_NEAR(solver.sim().external_work, work, 1e-9 * work);

  // The same ramp in 4 steps: the work summed step by step (trapezoidal, exact for this linear
  // response). The particles then leave the Gauss points by up to |v_top| / h = 1.8e-3 of an
  // element, so the quadrature is no longer exact (the particle stresses then differ from -p by up to
  // 2.1e-3 p): the work within that 2e-3 (measured 4.8e-4).
  const Spec stepped = dead_traction_spec(4);
  implicit::ImplicitMpmSolver<mesh::Q4> four(stepped, rectangle());
  run(four, stepped);
  std::printf("4 steps: external work / exact %.6f\n", four.sim().external_work / work);
  EXPECT_NEAR(four.sim().external_work, work, 2e-3 * work);
}

/// A block under a follower pressure p = 0.1 E on its `side` (normal along `axis`), one static step.
template <class E>
void check_follower(const std::string& mesh_json, const std::string& conditions, const std::string& side,
                    int axis, mesh::Mesh<E::kDim> background) {
  const double p = 0.1 * kYoung;
  const std::string box =
      E::kDim == 2 ? R"("min": [0, 0], "max": [2, 1])" : R"("min": [0, 0, 0], "max": [1, 1, 1])";
  const Spec spec = parse_spec(R"({
    "title": "follower pressure on a block",
    "mesh": )" + mesh_json + R"(,
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 1e6, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", )" +
                               box + R"(},
                "placement": "gauss", "particles_per_cell": 2}],
    "boundary_conditions": [)" +
                               conditions + R"(],
    "loads": {"tractions": [{"boundary": ")" +
                               side + R"(", "pressure": 1e5}]},
    "solver": {"type": "implicit_ul", "dt": 1, "end_time": 1,
               "implicit": {"analysis": "static", "newton": {"increment_tolerance": 1e-12}}},
    "output": {"every_time": 100}
  })");
  implicit::ImplicitMpmSolver<E> solver(spec, std::move(background));
  run(solver, spec);
  const auto& particles = solver.sim().particles;
  ASSERT_GT(particles.size(), 0u);
  for (std::size_t q = 0; q < particles.size(); ++q)
    for (int i = 0; i < E::kDim; ++i)
      for (int j = 0; j < E::kDim; ++j)
        EXPECT_NEAR(particles.stress[q](i, j), i == axis && j == axis ? -p : 0.0, 1e-8 * p) << i << j;
  // The block widened across the load (nu > 0): the pressure acted on the current, larger face.
  const int across = (axis + 1) % E::kDim;
  EXPECT_GT(particles.F[0](across, across), 1.0 + 1e-3);
}

TEST(SurfaceLoads, FollowerPressureGivesCauchyStressOnTheDeformedFace2D) {
  // The top (normal y) and the right side (normal x) of the block between smooth walls.
  for (const auto& [side, axis] : {std::pair<const char*, int>{"top", 1}, {"right", 0}}) {
    SCOPED_TRACE(side);
    check_follower<mesh::Q4>(
        R"({"element": "q4", "min": [0, 0], "max": [2, 1], "cells": [4, 2]})",
        R"({"type": "slip", "boundary": "bottom", "normal": "y"},
           {"type": "slip", "boundary": "left", "normal": "x"})",
        side, axis,
        mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 2, 4),
                                   mesh::AxisSpacing::uniform(0, 1, 2)));
  }
}

TEST(SurfaceLoads, FollowerPressureGivesCauchyStressOnTheDeformedFace3D) {
  const auto axis = mesh::AxisSpacing::uniform(0, 1, 2);
  check_follower<mesh::Hex8>(R"({"element": "hex8", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [2, 2, 2]})",
                             R"({"type": "slip", "boundary": "left", "normal": "x"},
                                {"type": "slip", "boundary": "bottom", "normal": "y"},
                                {"type": "slip", "boundary": "back", "normal": "z"})",
                             "front", 2, mesh::structured_box(axis, axis, axis));
}

}  // namespace
}  // namespace matpoint
