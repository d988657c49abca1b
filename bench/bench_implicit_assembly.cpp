// Assembly throughput of the particle-Newmark system (implicit/particle_newmark/): residual and AD
// Jacobian of every active element, scattered into the sparse matrix. Items per second = particle
// quadrature points per second. Also one numerical factorisation + solve of that matrix by each
// linear solver back-end.
// Mesh: cells x cells/2 unit Q9 elements, the left 3/4 filled with 9 particles per element (at the
// 3 x 3 Gauss points), bottom clamped, the rest inactive.
// Run: build/bench/matpoint_bench_implicit --benchmark_filter=Assembly
#include <benchmark/benchmark.h>
#include <omp.h>

#include "matpoint/implicit/linear_solver.hpp"
#include "matpoint/implicit/particle_newmark/element_flags.hpp"
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
        q.add(0, rule.points[g], X, 1000.0 * w, w, 0, Mat<2>::Identity(), Vec<2>(0.0, 9.81), 0);
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
