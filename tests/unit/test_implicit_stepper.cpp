// AT-1 free fall (Aulisa & Capodaglio extraction §12): a body away from every wall falls under
// gravity. A rigid translation has no stress, so the particle residual (20) enforces a_p = g at
// every step n >= 1, and the particles follow the discrete Newmark solution of eqs. (17)-(19):
//   with a^0 = 0 (the paper's start): u^1 = beta dt^2 g, v^1 = gamma dt g, then
//   u^{n+1} = dt v^n + dt^2 g / 2, v^n = (n - 1 + gamma) dt g;
//   with a^0 = g (A17): x - x^0 = g t^2 / 2 and v = g t exactly (Newmark integrates a constant
//   acceleration exactly).
// Checked to 1e-10 relative in 2-D (Q9) and 3-D (Hex8), with the soft stiffness on (a rigid
// translation has no gradient inside the active elements, so it adds no force).
// The equilibrium defect's work (StepReport::defect_work; docs/theory/implicit.md, "The energy
// audit"): with a^0 = g every step starts in equilibrium, e = 0; from a^0 = 0 the first step starts
// with e = -M g (M the body's mass), so (1/2) u~ . e = -(1/2) M beta dt^2 g^2 with u~ = beta dt^2 g,
// and 0 afterwards. Newmark's energy identity for the first step, Delta K - W_ext = (1/2) u~ . e -
// (beta - 1/4) dt^2 / 2 M (|a^1|^2 - |a^0|^2), holds on the particles' K and the work of gravity
// (from rest: K^1 - W = M g^2 dt^2 (gamma^2 / 2 - beta) = -(beta / 2 + (beta - 1/4) / 2) M g^2 dt^2).
#include <gtest/gtest.h>

#include "matpoint/implicit/particle_newmark/particle_newmark_stepper.hpp"
#include "matpoint/material/neo_hookean.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;

template <int D>
mesh::Mesh<D> box_mesh() {
  if constexpr (D == 2)
    return mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 10, 10),
                                      mesh::AxisSpacing::uniform(0, 10, 10));
  else
    return mesh::structured_box(mesh::AxisSpacing::uniform(0, 6, 6), mesh::AxisSpacing::uniform(0, 6, 6),
                                mesh::AxisSpacing::uniform(0, 6, 6));
}

template <class E>
void check_free_fall(bool a0_from_gravity) {
  constexpr int D = E::kDim;
  const auto mesh = box_mesh<D>();
  const double rho = 1000.0, E_mod = 1e6, nu = 0.3;
  const NeoHookean material{rho, E_mod * nu / ((1 + nu) * (1 - 2 * nu)), E_mod / (2 * (1 + nu))};
  ParticleNewmarkOptions<D> options;
  options.gravity[D - 1] = -9.81;
  options.initial_acceleration_from_body_force = a0_from_gravity;
  options.soft_stiffness = SoftStiffnessTable{{{5, 1e-2}, {E::kNodes, 1e-6}}};
  std::vector<char> dirichlet(static_cast<std::size_t>(mesh.node_count() * D), 0);
  for (const auto& [name, nodes] : mesh.node_sets)
    for (const Index n : nodes)
      for (int i = 0; i < D; ++i) dirichlet[static_cast<std::size_t>(n * D + i)] = 1;  // walls, far away
  ParticleNewmarkStepper<E, NeoHookean> stepper(mesh, {material}, options, dirichlet);

  // A block of particles around the middle, 0.25 apart, off the element faces.
  ParticleSet<D> particles;
  const double h = 0.25, low = D == 2 ? 4.125 : 2.125;
  const int per_side = D == 2 ? 8 : 7;
  for (int k = 0; k < (D == 3 ? per_side : 1); ++k)
    for (int j = 0; j < per_side; ++j)
      for (int i = 0; i < per_side; ++i) {
        Vec<D> x;
        x[0] = low + h * i, x[1] = low + h * j;
        if constexpr (D == 3) x[2] = low + h * k;
        const double volume = std::pow(h, D);
        particles.add(x, Vec<D>::Zero(), rho * volume, volume, Vec<D>::Constant(h), 0, 0);
      }
  const std::vector<Vec<D>> x0 = particles.x;
  ImplicitParticleState<D> state;
  stepper.initialize(particles, state);

  const double dt = 0.01, beta = options.newmark.beta, gamma = options.newmark.gamma, g = -9.81;
  double mass = 0.0;
  for (const double m : particles.mass) mass += m;
  const double scale = mass * g * g * dt * dt;  // the energies of one step
  double position = 0.0, velocity = 0.0;  // the expected vertical displacement and velocity
  for (int n = 1; n <= 10; ++n) {
    const StepReport report = stepper.step(particles, state, dt);
    ASSERT_TRUE(report.ok()) << report.newton.message;
    const double defect = !a0_from_gravity && n == 1 ? -0.5 * mass * beta * dt * dt * g * g : 0.0;
    EXPECT_NEAR(report.defect_work, defect, 1e-9 * scale) << "step " << n;
    if (n == 1) {
      double kinetic = 0.0, work = 0.0;
      for (std::size_t p = 0; p < particles.size(); ++p)
        kinetic += 0.5 * particles.mass[p] * particles.v[p].squaredNorm(),
            work += particles.mass[p] * g * (particles.x[p] - x0[p])[D - 1];
      const double beta_term = a0_from_gravity ? 0.0 : (beta - 0.25) * dt * dt / 2 * mass * g * g;
      EXPECT_NEAR(kinetic - work, report.defect_work - beta_term, 1e-9 * scale);
    }
    const double t = n * dt;
    if (a0_from_gravity) {
      position = 0.5 * g * t * t;
      velocity = g * t;
    } else {
      position += n == 1 ? beta * dt * dt * g : dt * velocity + 0.5 * dt * dt * g;
      velocity = (n - 1 + gamma) * dt * g;
    }
    for (std::size_t p = 0; p < particles.size(); ++p) {
      const Vec<D> dx = particles.x[p] - x0[p];
      for (int a = 0; a + 1 < D; ++a) {
        EXPECT_LT(std::abs(dx[a]), 1e-10 * std::abs(position));
        EXPECT_LT(std::abs(particles.v[p][a]), 1e-10 * std::abs(velocity));
      }
      EXPECT_NEAR(dx[D - 1], position, 1e-10 * std::abs(position)) << "step " << n << " particle " << p;
      EXPECT_NEAR(particles.v[p][D - 1], velocity, 1e-10 * std::abs(velocity)) << "step " << n;
      EXPECT_LT((particles.F[p] - Mat<D>::Identity()).norm(), 1e-10);
    }
  }
  // The body falls 0.05 m, less than its 0.125 m clearance to the next element row: the active set
  // never changes, so the sparse pattern and the solver's symbolic analysis are made once.
  EXPECT_EQ(stepper.linear_solver().stats().analyses, 1);
}

TEST(ImplicitStepper, FreeFallFollowsTheDiscreteNewmarkSolutionFromRest2D) {
  check_free_fall<mesh::Q9>(false);
}
TEST(ImplicitStepper, FreeFallIsExactlyHalfGTSquaredWithInitialAccelerationG2D) {
  check_free_fall<mesh::Q9>(true);
}
TEST(ImplicitStepper, FreeFallFollowsTheDiscreteNewmarkSolutionFromRest3D) {
  check_free_fall<mesh::Hex8>(false);
}
TEST(ImplicitStepper, FreeFallIsExactlyHalfGTSquaredWithInitialAccelerationG3D) {
  check_free_fall<mesh::Hex8>(true);
}

TEST(ImplicitStepper, AParticleOutsideTheMeshRefusesTheStepAndChangesNothing) {
  // Extraction A22: particles leaving the background grid are not covered by the paper; the step
  // reports them instead of throwing, and the particles keep their state.
  const auto mesh = box_mesh<2>();
  const NeoHookean material{1000.0, 1e6, 1e6};
  ParticleNewmarkOptions<2> options;
  options.gravity[1] = -9.81;
  std::vector<char> dirichlet(static_cast<std::size_t>(mesh.node_count() * 2), 0);
  ParticleNewmarkStepper<mesh::Q9, NeoHookean> stepper(mesh, {material}, options, dirichlet);
  ParticleSet<2> particles;
  particles.add(Vec<2>(5.1, 5.1), Vec<2>::Zero(), 1.0, 1e-3, Vec<2>::Constant(0.1), 0, 0);
  particles.add(Vec<2>(10.5, 5.1), Vec<2>::Zero(), 1.0, 1e-3, Vec<2>::Constant(0.1), 0, 0);
  const auto x0 = particles.x;
  ImplicitParticleState<2> state;
  const StepReport report = stepper.step(particles, state, 0.01);
  EXPECT_FALSE(report.ok());
  EXPECT_EQ(report.lost_particles, 1);
  EXPECT_EQ(particles.x, x0);
}

}  // namespace
