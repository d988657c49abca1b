// Throughput of one explicit step (particle-steps per second) for the bases and dimensions.
// Run: build/bench/matpoint_bench  (Release). Items per second = particle-steps per second.
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace matpoint;

template <int D> Spec block_spec(int cells_per_side, int ppc) {
  Spec spec;
  spec.grid.dim = D;
  for (int a = 0; a < D; ++a) {
    spec.grid.min[a] = 0.0;
    spec.grid.max[a] = 1.0;
    spec.grid.cell_size[a] = 1.0 / cells_per_side;
    spec.grid.cells[a] = cells_per_side;
  }
  MaterialSpec m;
  m.name = "rubber";
  m.model = MaterialModel::NeoHookean;
  m.density = 1000;
  m.youngs_modulus = 1e6;
  m.poisson_ratio = 0.3;
  m.lambda = m.youngs_modulus * 0.3 / (1.3 * 0.4);
  m.mu = m.youngs_modulus / 2.6;
  spec.materials.push_back(m);
  BodySpec body;
  body.shape = BodyShape::Box;
  for (int a = 0; a < D; ++a) {
    body.min[a] = 2.0 / cells_per_side;
    body.max[a] = 1.0 - 2.0 / cells_per_side;
    body.velocity[a] = a == 0 ? 1.0 : 0.0;
  }
  body.particles_per_cell = ppc;
  spec.bodies.push_back(body);
  spec.solver.shape = ShapeKind::BSpline2;
  return spec;
}

template <int D, class Basis> void BM_ExplicitStep(benchmark::State& state) {
  Spec spec = block_spec<D>(static_cast<int>(state.range(0)), 2);
  spec.solver.shape = Basis::width == 2 ? ShapeKind::Linear : ShapeKind::BSpline2;
  auto sim = build_simulation<D>(spec);
  ExplicitStepper<D, TensorStencils<D, Basis>> stepper(sim);
  const double dt = stable_time_step(sim);
  for (auto _ : state) stepper.step(dt);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(sim.particles.size()));
  state.counters["particles"] = static_cast<double>(sim.particles.size());
}

BENCHMARK(BM_ExplicitStep<2, LinearBasis>)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExplicitStep<2, QuadraticBSplineBasis>)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExplicitStep<3, LinearBasis>)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExplicitStep<3, QuadraticBSplineBasis>)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
