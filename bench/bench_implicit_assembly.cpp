// Assembly throughput of the particle-Newmark system (implicit/particle_newmark/): residual and AD
// Jacobian of every active element, scattered into the sparse matrix. Items per second = particle
// quadrature points per second. Also one numerical factorisation + solve of that matrix by each
// linear solver back-end.
// Mesh: cells x cells/2 unit Q9 elements, the left 3/4 filled with 9 particles per element (at the
// 3 x 3 Gauss points), bottom clamped, the rest inactive.
// Run: build/bench/matpoint_bench_implicit --benchmark_filter=Assembly
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <map>

#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/particle_newmark/element_flags.hpp"
#include "matpoint/implicit/particle_newmark/particle_newmark_stepper.hpp"
#include "matpoint/implicit/particle_newmark/particle_newmark_system.hpp"
#include "matpoint/material/neo_hookean.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;
using mesh::Q9;

struct Block {
  mesh::Mesh<2> mesh;
  ActiveSet set;
  ParticleQuadrature<Q9> q;
  std::vector<NeoHookean> materials{NeoHookean{1000.0, 1.5e6, 1.0e6}};
  std::vector<char> dirichlet;
  ParticleNewmarkSystem<Q9, NeoHookean> system;
  Index particles = 0;

  explicit Block(int cells) {
    mesh = mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, cells, cells),
                                      mesh::AxisSpacing::uniform(0, cells / 2, cells / 2));
    const auto& rule = mesh::gauss_rule<Q9>(3);
    std::vector<Index> host;
    for (Index e = 0; e < mesh.element_count(); ++e)
      if (e % cells < 3 * cells / 4)
        for (std::size_t g = 0; g < rule.points.size(); ++g) host.push_back(e);
    particles = static_cast<Index>(host.size());
    set = build_active_set(mesh.node_count(), 9, mesh.connectivity, host);
    const NewmarkCoefficients c(NewmarkParameters{}, 0.01);
    for (const Index e : set.active_elements) {
      const auto X = gather_nodes<Q9>(mesh.nodes, mesh.element_nodes(e));
      for (std::size_t g = 0; g < rule.points.size(); ++g) {
        const double w = rule.weights[g] * (X.transpose() * Q9::gradients(rule.points[g])).determinant();
        q.add(0, rule.points[g], X, 0, 1000.0 * w, w, 0, Mat<2>::Identity(), Vec<2>(0.0, 9.81), 0);
      }
      q.close_block();
    }
    dirichlet.assign(static_cast<std::size_t>(mesh.node_count() * 2), 0);
    for (const Index node : mesh.node_sets.at("bottom"))
      dirichlet[static_cast<std::size_t>(2 * node)] = dirichlet[static_cast<std::size_t>(2 * node + 1)] = 1;
    const auto flags = element_flags(set, 9, mesh.connectivity, FlagRule::Paper);
    const auto ce =
        soft_stiffness_factors(flags, SoftStiffnessTable{{{5, 1e-2}, {9, 1e-4}}}, FlagRule::Paper);
    ParticleNewmarkSystem<Q9, NeoHookean>::StepData data;
    data.mesh = &mesh;
    data.reference_nodes = mesh.nodes;
    data.set = &set;
    data.quadrature = &q;
    data.materials = materials;
    for (const double x : ce) data.soft_stiffness.push_back(materials[0].mu * x);
    data.dirichlet = dirichlet;
    data.options.inertia_coefficient = c.displacement;
    system.setup(std::move(data));
  }
};

void BM_AssemblyWithJacobian(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  Block b(static_cast<int>(state.range(0)));
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(b.system.dof_count(), 0.0, 1e-3), R;
  SparseMatrix K;
  for (auto _ : state) {
    b.system.assemble(u, R, &K);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.SetItemsProcessed(state.iterations() * b.particles);
  state.counters["dofs"] = static_cast<double>(b.system.dof_count());
}

void BM_AssemblyResidualOnly(benchmark::State& state) {
  omp_set_num_threads(1);
  Block b(static_cast<int>(state.range(0)));
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(b.system.dof_count(), 0.0, 1e-3), R;
  for (auto _ : state) {
    b.system.assemble(u, R, nullptr);
    benchmark::DoNotOptimize(R.data());
  }
  state.SetItemsProcessed(state.iterations() * b.particles);
}

/// One numerical factorisation (symbolic analysis done before) and one solve; range(1) = the
/// LinearSolverKind (0 umfpack, 1 klu, 2 bicgstab_ilut, 3 gmres_ilut).
void BM_FactorizeSolve(benchmark::State& state) {
  omp_set_num_threads(1);
  Block b(static_cast<int>(state.range(0)));
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(b.system.dof_count(), 0.0, 1e-3), R, x;
  SparseMatrix K;
  b.system.assemble(u, R, &K);
  LinearSolverOptions options;
  options.kind = static_cast<LinearSolverKind>(state.range(1));
  auto solver = make_linear_solver(options);
  state.SetLabel(std::string(solver->name()));
  solver->factorize(K, b.system.assembly().pattern_version());  // symbolic analysis outside the loop
  bool ok = true;
  for (auto _ : state) {
    ok = solver->factorize(K, b.system.assembly().pattern_version()) && solver->solve(R, x) && ok;
    benchmark::DoNotOptimize(x.data());
  }
  if (!ok) {
    state.SkipWithError(solver->message().c_str());
    return;
  }
  state.counters["dofs"] = static_cast<double>(b.system.dof_count());
  state.counters["relative_residual"] = (K * x - R).norm() / R.norm();
  state.counters["krylov_iterations"] = static_cast<double>(solver->stats().krylov_iterations) /
                                        static_cast<double>(std::max<long>(1, solver->stats().solves));
}

BENCHMARK(BM_AssemblyWithJacobian)
    ->Args({40, 1})
    ->Args({40, 2})
    ->Args({80, 1})
    ->Args({80, 2})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AssemblyResidualOnly)->Arg(80)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FactorizeSolve)->ArgsProduct({{40, 80}, {0, 1, 2, 3}})->Unit(benchmark::kMillisecond);

}  // namespace

// One implicit step of a disk (R = 0.5 m, E = 4.2e6 Pa, nu = 0.4, rho = 1000: Aulisa & Capodaglio's
// Test A material E1) resting on a clamped floor with the receding correction, on a cells x cells/2
// Q9 mesh of [0, 4] x [0, 2], 4 x 4 particles per element area: time per step and its shares.
// Arguments: cells, threads, LinearSolverKind (0 umfpack, 1 klu, 3 gmres_ilut).
namespace {

void BM_ParticleNewmarkStep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const int cells = static_cast<int>(state.range(0));
  const auto mesh =
      mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 4, cells),
                                 mesh::AxisSpacing::uniform(0, 2, cells / 2));
  const double E = 4.2e6, nu = 0.4, rho = 1000.0, h = 4.0 / cells;
  const NeoHookean material{rho, E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
  ParticleNewmarkOptions<2> options;
  options.gravity = Vec<2>(0.0, -9.81);
  options.soft_stiffness = SoftStiffnessTable{{{5, 1e-4}, {9, 1e-8}}};
  options.linear.kind = static_cast<LinearSolverKind>(state.range(2));
  std::vector<char> dirichlet(static_cast<std::size_t>(mesh.node_count() * 2), 0);
  for (const auto& side : {"bottom", "left", "right"})
    for (const Index n : mesh.node_sets.at(side)) dirichlet[2 * n] = dirichlet[2 * n + 1] = 1;
  std::map<std::pair<Index, int>, double> receding;
  for (const auto& [e, f] : mesh.boundary_faces.at("bottom")) receding[{e, f}] = 0.5;
  ParticleNewmarkStepper<Q9, NeoHookean> stepper(mesh, {material}, options, dirichlet, receding);
  ParticleSet<2> particles;
  const double spacing = h / 4, radius = 0.5;
  const Vec<2> centre(2.0, radius + 0.5 * spacing);
  for (double y = centre[1] - radius + 0.5 * spacing; y < centre[1] + radius; y += spacing)
    for (double x = centre[0] - radius + 0.5 * spacing; x < centre[0] + radius; x += spacing)
      if ((Vec<2>(x, y) - centre).norm() < radius)
        particles.add(Vec<2>(x, y), Vec<2>(0.2, 0.0), rho * spacing * spacing, spacing * spacing,
                      Vec<2>::Constant(spacing), 0, 0);
  ImplicitParticleState<2> extra;
  stepper.initialize(particles, extra);
  double assembly = 0.0, seconds = 0.0;
  long iterations = 0, steps = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const StepReport report = stepper.step(particles, extra, 0.01);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!report.ok()) {
      state.SkipWithError(report.newton.message.c_str());
      return;
    }
    assembly += report.assembly_seconds;
    iterations += report.newton.iterations();
    ++steps;
  }
  const auto& s = stepper.linear_solver().stats();
  state.counters["particles"] = static_cast<double>(particles.size());
  state.counters["newton_per_step"] = static_cast<double>(iterations) / static_cast<double>(steps);
  state.counters["assembly_share"] = assembly / seconds;
  state.counters["factorize_share"] = (s.analyze_seconds + s.factorize_seconds) / seconds;
  state.counters["solve_share"] = s.solve_seconds / seconds;
  state.counters["analyses"] = static_cast<double>(s.analyses);
  state.SetItemsProcessed(iterations * static_cast<long>(particles.size()));
}

BENCHMARK(BM_ParticleNewmarkStep)
    ->Args({40, 1, 0})
    ->Args({80, 1, 0})
    ->Args({80, 2, 0})
    ->Args({80, 1, 1})
    ->Args({80, 1, 3})
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond);

}  // namespace
