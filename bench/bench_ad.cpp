// Forward-mode AD scalar for the implicit element Jacobians: our Dual<N> (core/dual.hpp) against
// Eigen's AutoDiffScalar<Matrix<double, N, 1>> (unsupported/Eigen/AutoDiff), on one Q9 element
// with 9 particles: the particle residual of implicit/particle_newmark/particle_residual.hpp and its
// 18 x 18 Jacobian. Items per second = particle-quadrature points per second.
// Run: build/bench/matpoint_bench_implicit --benchmark_filter=AD
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "matpoint/implicit/ad_jacobian.hpp"
#include "matpoint/implicit/particle_newmark/particle_residual.hpp"
#include "matpoint/material/neo_hookean.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;
using mesh::Q9;
constexpr int kDofs = 18;

struct Element {
  ParticleQuadrature<Q9> q;
  NeoHookean material{1000.0, 1.0e6, 0.5e6};
  FaceCoefficients<Q9> receding{0.0, 0.0, 0.0, 0.0};
  ParticleResidualOptions options{1.0 / (0.3 * 0.01 * 0.01), true};
  std::array<double, kDofs> u{};
};

Element make_element() {
  Element e;
  NodeMatrix<Q9> x = Q9::reference_nodes();
  x(8, 0) += 0.05, x(4, 1) -= 0.03;  // a slightly curved element
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const Vec<2> xi(-0.7 + 0.65 * a, -0.6 + 0.6 * b);
      Mat<2> F;
      F << 1.02, 0.01 * a, -0.02 * b, 0.99;
      e.q.add(0, xi, x, 0, 0.1, 1e-4, 0, F, Vec<2>(0.3, -9.81), 0);
    }
  e.q.close_block();
  for (int i = 0; i < kDofs; ++i) e.u[static_cast<std::size_t>(i)] = 1e-3 * std::sin(1.7 * i + 0.3);
  return e;
}

void BM_ParticleResidual_Double(benchmark::State& state) {
  const Element e = make_element();
  std::array<double, kDofs> r{};
  for (auto _ : state) {
    r.fill(0.0);
    add_particle_residual<Q9>(e.q, 0, 9, &e.material, e.receding, e.options, e.u.data(), r.data());
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations() * 9);
}

void BM_ParticleJacobian_AD_Dual(benchmark::State& state) {
  const Element e = make_element();
  std::array<double, kDofs> r{};
  std::array<double, kDofs * kDofs> K{};
  for (auto _ : state) {
    residual_and_jacobian<kDofs>(
        e.u.data(),
        [&](const auto* u, auto* res) {
          add_particle_residual<Q9>(e.q, 0, 9, &e.material, e.receding, e.options, u, res);
        },
        r.data(), K.data());
    benchmark::DoNotOptimize(K);
  }
  state.SetItemsProcessed(state.iterations() * 9);
}

void BM_ParticleJacobian_AD_EigenAutoDiff(benchmark::State& state) {
  using S = Eigen::AutoDiffScalar<Eigen::Matrix<double, kDofs, 1>>;
  const Element e = make_element();
  std::array<double, kDofs> r{};
  std::array<double, kDofs * kDofs> K{};
  for (auto _ : state) {
    std::array<S, kDofs> us, rs;
    for (int i = 0; i < kDofs; ++i) {
      us[static_cast<std::size_t>(i)] = S(e.u[static_cast<std::size_t>(i)], kDofs, i);
      rs[static_cast<std::size_t>(i)] = S(0.0, Eigen::Matrix<double, kDofs, 1>::Zero());
    }
    add_particle_residual<Q9>(e.q, 0, 9, &e.material, e.receding, e.options, us.data(), rs.data());
    for (int i = 0; i < kDofs; ++i) {
      r[static_cast<std::size_t>(i)] = rs[static_cast<std::size_t>(i)].value();
      for (int j = 0; j < kDofs; ++j)
        K[static_cast<std::size_t>(i * kDofs + j)] = rs[static_cast<std::size_t>(i)].derivatives()[j];
    }
    benchmark::DoNotOptimize(K);
  }
  state.SetItemsProcessed(state.iterations() * 9);
}

BENCHMARK(BM_ParticleResidual_Double);
BENCHMARK(BM_ParticleJacobian_AD_Dual);
BENCHMARK(BM_ParticleJacobian_AD_EigenAutoDiff);

}  // namespace

BENCHMARK_MAIN();
