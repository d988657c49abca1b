// Per-point cost of the meshfree clouds and shape functions (Iaconeta et al. 2017 §4.2): the
// cell-list radius search, MLS and LME on the found cloud, and the whole per-step evaluation.
// Nodes: a regular grid (spacing h, jittered by 0.2 h); points: 2^D per cell at the Gauss points'
// positions (as the paper's material points). R = 2 sqrt(2) h, R_eff = R / 2, gamma = 1.8.
// Counters: ns per point (the time / points) and the mean cloud size.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "matpoint/shape/meshfree_stencils.hpp"

namespace {

using namespace matpoint;

template <int D>
struct Setup {
  std::vector<Vec<D>> nodes, points;
  MeshfreeParameters par;

  explicit Setup(int n) {
    par.spacing = 1.0 / (n - 1);
    const double h = par.spacing, g = 0.5 / std::sqrt(3.0);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-0.2 * h, 0.2 * h);
    std::array<int, D> i{};
    while (true) {
      Vec<D> x;
      for (int a = 0; a < D; ++a) x[a] = i[a] * h + u(rng);
      nodes.push_back(x);
      bool cell = true;
      for (int a = 0; a < D; ++a) cell = cell && i[a] < n - 1;
      for (int corner = 0; cell && corner < (1 << D); ++corner) {
        Vec<D> p;
        for (int a = 0; a < D; ++a) p[a] = (i[a] + 0.5 + ((corner >> a) & 1 ? g : -g)) * h;
        points.push_back(p);
      }
      int a = 0;
      while (a < D && ++i[a] == n) i[a] = 0, ++a;
      if (a == D) break;
    }
  }
};

template <int D>
const Setup<D>& setup() {
  static const Setup<D> s(D == 2 ? 101 : 21);
  return s;
}

template <int D>
void BM_Search(benchmark::State& state) {
  const auto& s = setup<D>();
  const NodeCellList<D> list(s.nodes, s.par.radius() / static_cast<double>(state.range(0)));
  std::vector<NodeDistance> found;
  std::size_t total = 0;
  for (auto _ : state) {
    total = 0;
    for (const auto& x : s.points) {
      found.clear();
      list.within(x, s.par.radius(), found);
      total += found.size();
    }
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["ns_per_point"] =
      benchmark::Counter(static_cast<double>(state.iterations() * s.points.size()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cloud"] = static_cast<double>(total) / s.points.size();
}

/// The shape functions alone, on clouds gathered once beforehand.
template <int D, MeshfreeBasis B>
void BM_Shape(benchmark::State& state) {
  const auto& s = setup<D>();
  const NodeCellList<D> list(s.nodes, s.par.radius());
  std::vector<std::vector<Vec<D>>> clouds(s.points.size());
  std::vector<NodeDistance> found;
  std::size_t total = 0;
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    found.clear();
    list.within(s.points[p], s.par.radius(), found);
    for (const auto& f : found) clouds[p].push_back(s.nodes[f.node]);
    total += found.size();
  }
  std::vector<double> N(200);
  std::vector<Vec<D>> dN(200);
  LmeParameters lme;
  lme.beta = s.par.beta();
  for (auto _ : state) {
    for (std::size_t p = 0; p < s.points.size(); ++p) {
      const std::size_t n = clouds[p].size();
      if constexpr (B == MeshfreeBasis::Mls)
        mls_shape_functions<D>(s.points[p], clouds[p], s.par.dilation(), std::span(N.data(), n),
                               std::span(dN.data(), n), s.par.mls_weight, s.par.radius());
      else
        lme_shape_functions<D>(s.points[p], clouds[p], lme, std::span(N.data(), n), std::span(dN.data(), n));
    }
    benchmark::DoNotOptimize(N.data());
  }
  state.counters["ns_per_point"] =
      benchmark::Counter(static_cast<double>(state.iterations() * s.points.size()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cloud"] = static_cast<double>(total) / s.points.size();
}

/// Search, evaluation and storage of all points: one step's cost of the GMM's shape functions.
template <int D, MeshfreeBasis B>
void BM_Stencils(benchmark::State& state) {
  const auto& s = setup<D>();
  MeshfreeParameters par = s.par;
  par.basis = B;
  MeshfreeStencils<D> out;
  for (auto _ : state) {
    build_meshfree_stencils<D>(s.points, s.nodes, par, out);
    benchmark::DoNotOptimize(out.N.data());
  }
  state.counters["ns_per_point"] =
      benchmark::Counter(static_cast<double>(state.iterations() * s.points.size()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cloud"] = static_cast<double>(out.node.size()) / s.points.size();
}

BENCHMARK(BM_Search<2>)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);  // cell = R / arg
BENCHMARK(BM_Search<3>)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Shape<2, MeshfreeBasis::Mls>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Shape<2, MeshfreeBasis::Lme>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Shape<3, MeshfreeBasis::Mls>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Shape<3, MeshfreeBasis::Lme>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils<2, MeshfreeBasis::Mls>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils<2, MeshfreeBasis::Lme>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils<3, MeshfreeBasis::Mls>)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils<3, MeshfreeBasis::Lme>)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
