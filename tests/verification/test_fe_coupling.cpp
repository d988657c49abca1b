// The monolithic MPM-FEM coupling (Aulisa & Capodaglio §4-5, extraction AT-5, AT-6, AT-10, AT-11):
// a small elastic disk falls under gravity onto a clamped FE plate that carries the background grid
// (examples/bouncing-disk scaled down so that the test takes seconds: a coarse disk, one refinement).
//  - AT-6: no particle is ever inside an FE element, and the background's reference nodes on the
//    interface are the plate's deformed nodes (x~ = X + u_fem, eq. (8a)); AT-5: the system size is
//    fixed (every node keeps its dofs).
//  - The fall is arrested no later than 0.02 s after the free-fall time of the clearance,
//    sqrt(2 h / g) (extraction AT-10), and not before the disk enters the background elements on the
//    plate (height 0.092 m here): the particle formulation feels a wall as soon as a particle sits in
//    an element that touches it (§5), sqrt(2 (h - 0.092) / g).
//  - With the receding correction (C_c = 0.5) and the plate's inertia of the authors' code (unit
//    density, as the example) the disk bounces back to 90-105 % of its drop (the paper's Fig. 12:
//    no damping of the bounces); AT-11: with C_c = 0 it sticks and bounces lower.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/mesh/point_locator.hpp"
#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace {

constexpr double kPlateTop = -1.52, kGravity = 9.81;
// Aulisa & Capodaglio Fig. 12: the disk bounces back to its drop height (no damping). The band of the
// bouncing-disk example's checks: 90 % to 105 % of the drop.
constexpr double kLowestApex = 0.90, kHighestApex = 1.05;

/// The bouncing-disk example with a coarse disk (N_theta0 = 60), dropped from `height` (its lowest
/// point above the plate), steps of 0.002 s far from the plate and 5e-4 s near it.
Spec small_bounce_spec(double height, double receding, double e_disk) {
  Spec spec = test::load_example("bouncing-disk");
  spec.bodies[0].core_divisions = 60;
  const double centre = kPlateTop + height + 0.16;
  spec.bodies[0].center = {0, centre, 0};
  spec.output.probes[0].position = {0, centre, 0};
  spec.materials[0].youngs_modulus = e_disk;
  spec.materials[0].mu = e_disk / 2.8;  // nu = 0.4
  spec.materials[0].lambda = e_disk / 0.7;
  spec.fe_bodies[0].interface_receding = receding;
  spec.solver.implicit.dt_by_position = TimeFunction{{kPlateTop + 0.092, kPlateTop + 0.2}, {5e-4, 2e-3}};
  return spec;
}

struct BounceRecord {
  std::vector<double> time, centre_y;
  bool particle_in_fe = false, interface_follows_plate = true, size_fixed = true;
};

BounceRecord run_bounce(const Spec& spec, double end_time) {
  mesh::AxisSpacing x, y;  // mesh.lines, refined as the run refines them
  x.breaks = spec.mesh.lines[0];
  y.breaks = spec.mesh.lines[1];
  const mesh::Mesh<2> m =
      mesh::refine(mesh::structured_rectangle(mesh::ElementShape::Q9, x, y), spec.mesh.refine);
  implicit::ImplicitMpmSolver<mesh::Q9> solver(spec, m);
  auto& sim = solver.sim();
  std::size_t centre = 0;  // the particle nearest the disk's centre
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    if ((sim.particles.x[p] - sim.particles.x[centre]).norm() > 0 &&
        std::abs(sim.particles.x[p][1] - spec.bodies[0].center[1]) + std::abs(sim.particles.x[p][0]) <
            std::abs(sim.particles.x[centre][1] - spec.bodies[0].center[1]) +
                std::abs(sim.particles.x[centre][0]))
      centre = p;
  const auto& fe = solver.fe_bodies_state();
  mesh::PointLocator<2> all(solver.mesh(), solver.mesh().nodes);
  BounceRecord out;
  const Index dofs = solver.mesh().node_count() * 2;
  while (sim.time < end_time) {
    solver.step(solver.time_step());
    out.time.push_back(sim.time);
    out.centre_y.push_back(sim.particles.x[centre][1]);
    all.update(solver.reference_nodes());
    for (const auto& x : sim.particles.x)
      if (const auto loc = all.locate(x); loc &&
                                          fe.element_mask()[static_cast<std::size_t>(loc->element)] != 0 &&
                                          mesh::Q9::contains(loc->xi, -1e-9))
        out.particle_in_fe = true;
    for (Index n = 0; n < solver.mesh().node_count(); ++n)
      if (fe.node_mask()[static_cast<std::size_t>(n)] != 0 &&
          (solver.reference_nodes()[static_cast<std::size_t>(n)] -
           solver.mesh().nodes[static_cast<std::size_t>(n)] - fe.displacement[static_cast<std::size_t>(n)])
                  .norm() > 1e-14)
        out.interface_follows_plate = false;
    out.size_fixed = out.size_fixed && solver.last_nodal_increment().size() == dofs;
  }
  return out;
}

/// The first time the centre's fall is stopped (its downward velocity drops below half the free-fall one).
double first_contact(const BounceRecord& r, double y0) {
  for (std::size_t k = 1; k < r.time.size(); ++k) {
    const double v = (r.centre_y[k] - r.centre_y[k - 1]) / (r.time[k] - r.time[k - 1]);
    const double free_fall = kGravity * r.time[k];
    if (y0 - r.centre_y[k] > 0.01 && -v < 0.5 * free_fall) return r.time[k];
  }
  return std::numeric_limits<double>::infinity();
}

/// The highest centre after the first contact, as a fraction of the drop (relative to the rest position).
double rebound_fraction(const BounceRecord& r, double contact, double y0) {
  double lowest = y0, apex = -1e9;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    if (r.time[k] < contact) continue;
    lowest = std::min(lowest, r.centre_y[k]);
    if (r.centre_y[k] > apex && r.time[k] > contact + 0.05) apex = r.centre_y[k];
  }
  const double rest = kPlateTop + 0.16;
  return (apex - rest) / (y0 - rest);
}

TEST(FeCoupling, DiskFallsOntoThePlateWithoutEnteringItAndReboundsWithTheReceding) {
  const double height = 0.3;  // clearance: first contact at sqrt(2 h / g) = 0.247 s
  const double expected_contact = std::sqrt(2 * height / kGravity);
  const Spec corrected = small_bounce_spec(height, 0.5, 5.91e7);
  const double y0 = corrected.bodies[0].center[1];
  const BounceRecord bounce = run_bounce(corrected, 0.6);
  const double contact = first_contact(bounce, y0);
  const double rebound = rebound_fraction(bounce, contact, y0);
  std::printf("C_c = 0.5: contact at %.4f s (free fall %.4f s), rebound %.3f of the drop\n", contact,
              expected_contact, rebound);
  EXPECT_FALSE(bounce.particle_in_fe);
  EXPECT_TRUE(bounce.interface_follows_plate);
  EXPECT_TRUE(bounce.size_fixed);
  EXPECT_LE(contact, expected_contact + 0.02);
  EXPECT_GE(contact, std::sqrt(2 * (height - 0.092) / kGravity));
  EXPECT_GE(rebound, kLowestApex);
  EXPECT_LE(rebound, kHighestApex);
}

TEST(FeCoupling, WithoutTheRecedingCorrectionTheDiskSticksAndLosesItsBounce) {
  // AT-11 on the same drop: with C_c = 0 the plate's interface nodes, shared with the elements the
  // disk's bottom sits in, hold the receding disk back (the artificial sticky force of §5), and the
  // energy it takes is missing from the bounce: below the band that C_c = 0.5 reaches.
  const double height = 0.3;
  const Spec sticky = small_bounce_spec(height, 0.0, 5.91e7);
  const double y0 = sticky.bodies[0].center[1];
  const BounceRecord bounce = run_bounce(sticky, 0.6);
  const double rebound = rebound_fraction(bounce, first_contact(bounce, y0), y0);
  std::printf("C_c = 0: rebound %.3f of the drop\n", rebound);
  EXPECT_LT(rebound, kLowestApex);
}

}  // namespace
}  // namespace matpoint
