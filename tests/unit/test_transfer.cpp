// Particle-grid transfers: P2G conserves mass and momentum, G2P (PIC) returns the grid momentum to
// the particles, a uniform velocity field (rigid translation) gives zero velocity gradient and zero
// stress. All identities are exact in exact arithmetic, so the bounds are round-off.
#include <gtest/gtest.h>

#include <random>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

template <int D>
Simulation<D> random_particles(int cells, ShapeKind shape, const Vec<D>& drift) {
  Simulation<D> sim;
  std::array<int, D> n{};
  n.fill(cells);
  sim.grid = Grid<D>(Vec<D>::Zero(), Vec<D>::Constant(1.0 / cells), n, 0);
  sim.fields.resize(sim.grid.node_count);
  sim.materials.push_back(NeoHookean{1000.0, 1e6, 5e5, NeoHookeanVolumetric::LogJ});
  sim.solver.shape = shape;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    Vec<D> x, v;
    for (int a = 0; a < D; ++a) {
      x[a] = u(rng);
      v[a] = drift[a] + (drift.norm() > 0 ? 0.0 : u(rng) - 0.5);
    }
    sim.particles.add(x, v, 0.5 + u(rng), 1e-3, Vec<D>::Constant(0.5 / cells), 0, 0);
  }
  sort_by_cell(sim.grid, sim.particles);
  return sim;
}

template <int D, class Basis>
void check_conservation() {
  auto sim =
      random_particles<D>(6, Basis::width == 2 ? ShapeKind::Linear : ShapeKind::BSpline2, Vec<D>::Zero());
  TensorStencils<D, Basis> stencils;
  stencils.evaluate(sim.grid, sim.particles);
  scatter_to_grid<kScatterMass | kScatterMomentum>(sim.grid, stencils, sim.particles, Vec<D>(Vec<D>::Zero()),
                                                   sim.fields);
  double particle_mass = 0, grid_mass = 0;
  Vec<D> particle_momentum = Vec<D>::Zero(), grid_momentum = Vec<D>::Zero();
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    particle_mass += sim.particles.mass[p];
    particle_momentum += sim.particles.mass[p] * sim.particles.v[p];
  }
  for (Index i = 0; i < sim.grid.node_count; ++i) {
    grid_mass += sim.fields.mass[i];
    grid_momentum += sim.fields.momentum[i];
  }
  EXPECT_NEAR(grid_mass, particle_mass, 1e-12 * particle_mass);
  EXPECT_LT((grid_momentum - particle_momentum).norm(), 1e-12 * particle_mass);

  // G2P with PIC and zero force: V = S v, and sum M_p V_p = sum_i m_i v_i = sum_i p_i.
  lumped_velocity(sim.fields, 0.0, sim.fields.velocity_new);
  for (auto& a : sim.fields.acceleration) a.setZero();
  const TransferParameters pic{VelocityTransfer::PIC, 1.0, 0.0};
  gather_and_move(sim.grid, stencils, sim.fields, sim.particles, pic, 0.0, false, Vec<D>(Vec<D>::Zero()));
  Vec<D> after = Vec<D>::Zero();
  for (std::size_t p = 0; p < sim.particles.size(); ++p) after += sim.particles.mass[p] * sim.particles.v[p];
  EXPECT_LT((after - particle_momentum).norm(), 1e-12 * particle_mass);
}

TEST(Transfer, ScatterAndPicGatherConserveMassAndMomentum) {
  check_conservation<1, LinearBasis>();
  check_conservation<2, LinearBasis>();
  check_conservation<3, LinearBasis>();
  check_conservation<1, QuadraticBSplineBasis>();
  check_conservation<2, QuadraticBSplineBasis>();
  check_conservation<3, QuadraticBSplineBasis>();
}

template <int D, class Basis>
void check_rigid_translation(UpdateScheme scheme) {
  Vec<D> drift = Vec<D>::Zero();
  drift[0] = 0.3;
  drift[D - 1] += -0.2;
  auto sim = random_particles<D>(6, Basis::width == 2 ? ShapeKind::Linear : ShapeKind::BSpline2, drift);
  for (auto& x : sim.particles.x) x = 0.25 * Vec<D>::Ones() + 0.5 * x;  // keep clear of the edges
  sim.solver.scheme = scheme;
  ExplicitStepper<D, TensorStencils<D, Basis>> stepper(sim);
  for (int k = 0; k < 20; ++k) stepper.step(1e-3);
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    EXPECT_LT(sim.particles.stress[p].norm(), 1e-6) << "stress of a rigid translation, E = 1.25e6";
    EXPECT_LT((sim.particles.v[p] - drift).norm(), 1e-13);
    EXPECT_LT((sim.particles.F[p] - Mat<D>::Identity()).norm(), 1e-12);
  }
}

TEST(Transfer, RigidTranslationProducesNoStress) {
  for (auto scheme : {UpdateScheme::USL, UpdateScheme::USF, UpdateScheme::MUSL, UpdateScheme::USAVG}) {
    check_rigid_translation<1, LinearBasis>(scheme);
    check_rigid_translation<2, LinearBasis>(scheme);
    check_rigid_translation<3, QuadraticBSplineBasis>(scheme);
    check_rigid_translation<2, QuadraticBSplineBasis>(scheme);
  }
}

}  // namespace
