// The MLS machinery of Gong 2015's IMPM (ch. 3, 5): extraction tests U1, U2 (reproduction, shift
// invariance, Shepard fallback) and U7 (cell-centre assembly of a uniform state), in 1-D to 3-D.
#include <gtest/gtest.h>

#include <random>

#include "matpoint/explicit/mls_mapping.hpp"
#include "matpoint/shape/mls.hpp"

namespace {

using namespace matpoint;

template <int D>
std::vector<Vec<D>> stratified_points(int cells, int per_cell, double h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec<D>> x;
  int total = 1;
  for (int a = 0; a < D; ++a) total *= cells * per_cell;
  for (int k = 0; k < total; ++k) {  // one random point in each sub-cell
    Vec<D> p;
    for (int a = 0, rest = k; a < D; ++a, rest /= cells * per_cell)
      p[a] = h * ((rest % (cells * per_cell)) + u(rng)) / per_cell;
    x.push_back(p);
  }
  return x;
}

/// The MLS fit at `at` of the fields [1, x_1 .. x_D, f(x)] from the points (cubic weight, radius 2h).
template <int D>
Eigen::Matrix<double, D + 2, 1> fit(const Vec<D>& at, const std::vector<Vec<D>>& points, double h,
                                    const std::vector<double>& f, MlsStatus* status = nullptr) {
  MlsSums<D, D + 2> sums;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Vec<D> d = (points[p] - at) / h;
    double w = 1.0;
    for (int a = 0; a < D; ++a) w *= cubic_weight(std::abs(d[a]));
    if (w == 0.0) continue;
    Eigen::Matrix<double, D + 2, 1> u;
    u[0] = 1.0;
    u.template segment<D>(1) = points[p];
    u[D + 1] = f[p];
    sums.add(w, d, u);
  }
  Eigen::Matrix<double, D + 2, 1> out;
  const MlsStatus s = sums.solve(1, out);
  if (status != nullptr) *status = s;
  return out;
}

// Extraction U2: sum_p Phi_p = 1 and sum_p Phi_p x_p = x at the nodes (relative error < 1e-10),
// and shift invariance: translating every point and the node by 1e3 changes nothing (< 1e-10).
template <int D>
void check_reproduction_and_shift() {
  const double h = 0.125;
  const int cells = D == 3 ? 4 : 8;
  const auto x = stratified_points<D>(cells, 2, h, 11);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> f;
  for (std::size_t p = 0; p < x.size(); ++p) f.push_back(n(rng));  // an arbitrary field
  Vec<D> shift = Vec<D>::Constant(1e3);
  std::vector<Vec<D>> shifted;
  for (const auto& p : x) shifted.push_back(p + shift);
  int nodes = 0;
  for (int k = 0; k < (D == 1 ? cells + 1 : (D == 2 ? (cells + 1) * (cells + 1) : 125)); ++k) {
    Vec<D> node;
    for (int a = 0, rest = k; a < D; ++a, rest /= cells + 1) node[a] = h * (rest % (cells + 1));
    MlsStatus status{};
    const auto u = fit<D>(node, x, h, f, &status);
    ASSERT_EQ(status, MlsStatus::Fit) << "node " << node.transpose();
    EXPECT_NEAR(u[0], 1.0, 1e-10);
    for (int a = 0; a < D; ++a) EXPECT_NEAR(u[1 + a], node[a], 1e-10 * std::max(1.0, std::abs(node[a])));
    const auto us = fit<D>(node + shift, shifted, h, f);
    EXPECT_NEAR(us[D + 1], u[D + 1], 1e-10 * std::max(1.0, std::abs(u[D + 1])))
        << "node " << node.transpose();
    ++nodes;
  }
  EXPECT_GT(nodes, 8);
}

TEST(MlsSums, ReproducesLinearFieldsAndIsShiftInvariant1D) { check_reproduction_and_shift<1>(); }
TEST(MlsSums, ReproducesLinearFieldsAndIsShiftInvariant2D) { check_reproduction_and_shift<2>(); }
TEST(MlsSums, ReproducesLinearFieldsAndIsShiftInvariant3D) { check_reproduction_and_shift<3>(); }

// Extraction A16: a singular moment matrix (2-D points on one line: no information across it)
// falls back to Shepard, sum w u / sum w, and says so; no point at all is Empty.
TEST(MlsSums, FallsBackToShepardWhenTheMomentMatrixIsSingular) {
  MlsSums<2, 1> sums;
  const double u[3] = {1.0, 2.0, 4.0}, w[3] = {0.5, 0.25, 0.25};
  for (int p = 0; p < 3; ++p) sums.add(w[p], Vec<2>(0.3 * p - 0.3, 0.2), Eigen::Matrix<double, 1, 1>(u[p]));
  Eigen::Matrix<double, 1, 1> out;
  EXPECT_EQ(sums.solve(1, out), MlsStatus::Shepard);
  EXPECT_NEAR(out[0], (0.5 * 1 + 0.25 * 2 + 0.25 * 4) / 1.0, 1e-15);
  MlsSums<2, 1> empty;
  EXPECT_EQ(empty.solve(1, out), MlsStatus::Empty);
}

// Extraction U1: the quadratic and cubic B-splines (5.1), (5.2) are partitions of unity on the lattice.
TEST(MlsWeights, SplinesArePartitionsOfUnity) {
  for (double xi = 0.0; xi < 1.0; xi += 0.0625) {
    double w2 = 0.0, w3 = 0.0;
    for (int k = -3; k <= 3; ++k) {
      w2 += quadratic_weight(std::abs(xi - k));
      w3 += cubic_weight(std::abs(xi - k));
    }
    EXPECT_NEAR(w2, 1.0, 1e-14);
    EXPECT_NEAR(w3, 1.0, 1e-14);
  }
}

/// Particles filling [0, 1]^D with `ppc` per direction per cell, uniform density and stress.
template <int D>
ParticleSet<D> uniform_block(int cells, int ppc, double rho, const Mat<D>& stress) {
  ParticleSet<D> ps;
  const double h = 1.0 / cells, dp = h / ppc;
  int n = 1;
  for (int a = 0; a < D; ++a) n *= cells * ppc;
  for (int k = 0; k < n; ++k) {
    Vec<D> x;
    for (int a = 0, rest = k; a < D; ++a, rest /= cells * ppc) x[a] = (rest % (cells * ppc) + 0.5) * dp;
    const double v = std::pow(dp, D);
    ps.add(x, Vec<D>::Zero(), rho * v, v, Vec<D>::Constant(dp), 0, 0);
    ps.stress.back() = stress;
  }
  return ps;
}

template <int D>
Grid<D> unit_grid(int cells) {
  std::array<int, D> c;
  c.fill(cells);
  return Grid<D>(Vec<D>::Zero(), Vec<D>::Constant(1.0 / cells), c, 0);
}

// Extraction U7: IMPM's cell-centre assembly of a uniform state (rho_p = rho0, sigma_p = const):
// m_i = rho0 h^D N-weighted: rho0 h in 1-D inside, rho0 h / 2 at the ends (2-D: h^2, h^2/2 on edges,
// h^2/4 at corners); f_int = 0 at interior nodes and -grad N . sigma Omega (the cut) on the boundary.
// The Gauss-point and particle-volume-fraction extensions assemble the same for full cells.
template <int D>
void check_uniform_assembly(const MlsSpec& spec) {
  const int cells = 4;
  const double rho = 1e3, h = 1.0 / cells;
  Mat<D> sigma = Mat<D>::Zero();
  for (int a = 0; a < D; ++a) sigma(a, a) = 1e5 * (a + 1);
  if constexpr (D > 1) sigma(0, 1) = sigma(1, 0) = 3e4;
  const auto grid = unit_grid<D>(cells);
  const auto ps = uniform_block<D>(cells, 2, rho, sigma);
  GridFields<D> fields;
  fields.resize(grid.node_count);
  MlsMapping<D> mls(spec);
  mls.bin(grid, ps);
  mls.template cell_quadrature<true, true>(grid, ps, Vec<D>::Zero(), nullptr, fields);
  for (Index i = 0; i < grid.node_count; ++i) {
    const auto ijk = grid.node_coords(i);
    double share = 1.0;  // the fraction of the node's support inside the body
    Vec<D> cut = Vec<D>::Zero();
    for (int a = 0; a < D; ++a) {
      const bool end = ijk[a] == 0 || ijk[a] == cells;
      if (end) share *= 0.5;
      if (end) cut[a] = ijk[a] == 0 ? 1.0 : -1.0;  // the inward normal of the face the node lies on
    }
    EXPECT_NEAR(fields.mass[i], rho * std::pow(h, D) * share, 1e-9 * rho * std::pow(h, D)) << "node " << i;
    // f_i = -sum_c sigma grad N_i(x_c) Omega_c: zero inside; on a face of inward normal e_a the
    // traction sigma e_a times the node's share of the face, h^(D-1) halved for each other end axis.
    Vec<D> expected = Vec<D>::Zero();
    for (int a = 0; a < D; ++a)
      if (cut[a] != 0.0) expected += cut[a] * sigma.col(a) * std::pow(h, D - 1) * (share / 0.5);
    for (int a = 0; a < D; ++a)
      EXPECT_NEAR(fields.force[i][a], expected[a], 1e-9 * 1e5 * std::pow(h, D - 1))
          << "node " << i << " axis " << a;
  }
  EXPECT_EQ(mls.statistics().fallbacks, 0);
}

TEST(ImpmAssembly, UniformStateCellCentre1D) { check_uniform_assembly<1>({}); }
TEST(ImpmAssembly, UniformStateCellCentre2D) { check_uniform_assembly<2>({}); }
TEST(ImpmAssembly, UniformStateCellCentre3D) { check_uniform_assembly<3>({}); }
TEST(ImpmAssembly, UniformStateGaussAndVolumeFraction2D) {
  check_uniform_assembly<2>({1, CellQuadrature::Gauss2, CellVolume::ParticleFraction});
}

// Eq. (5.15) with the linear basis reproduces a linear velocity field exactly at every node, the
// boundary nodes included (the mass-weighted Shepard map of MPM does not, Gong Table 4.1), so
// the grid momentum is m_i (a + B x_i).
TEST(ImpmMapping, NodeVelocityReproducesALinearField2D) {
  const int cells = 4;
  const auto grid = unit_grid<2>(cells);
  auto ps = uniform_block<2>(cells, 2, 1e3, Mat<2>::Zero());
  const Vec<2> a(0.5, -1.0);
  Mat<2> B;
  B << 2.0, -3.0, 0.25, 1.5;
  for (std::size_t p = 0; p < ps.size(); ++p) ps.v[p] = a + B * ps.x[p];
  std::vector<double> mass(grid.node_count, 2.0);
  std::vector<Vec<2>> momentum(grid.node_count);
  MlsMapping<2> mls;
  mls.bin(grid, ps);
  mls.node_momentum(grid, ps, mass, 0.0, momentum);
  for (Index i = 0; i < grid.node_count; ++i) {
    const Vec<2> expected = 2.0 * (a + B * grid.node_position(i));
    EXPECT_NEAR((momentum[i] - expected).norm(), 0.0, 1e-12) << "node " << i;
  }
  EXPECT_EQ(mls.statistics().evaluations, grid.node_count);
  EXPECT_EQ(mls.statistics().fallbacks, 0);
}

}  // namespace
