// The moving-least-squares transfers of Gong 2015's improved MPM (ch. 5, §5.4) and improved CPDI
// (§6.6); docs/theory/impm.md. Every reconstruction is a gather: a loop over the evaluation
// points (nodes, cell points) that visits the particles of the nearby cells (ParticleBins), so the
// threads never write to the same entry and the result does not depend on the thread count.
//   velocity:  v_i = sum_p Phi_p(x_i) v_p, linear MLS, cubic weight                          (5.15)
//   cells:     rho_c, sigma_c, b_c = sum_p Q_p(x_c) (rho_p, sigma_p, b_p), quadratic weight   (5.16), (5.17)
//   nodes:     m_i = sum_c rho_c N_i(x_c) Omega_c                                             (5.14)
//              f_i = -sum_c grad N_i(x_c) . sigma_c Omega_c + sum_c N_i(x_c) rho_c b_c Omega_c  (5.9), (5.10)
// Extensions (not in the dissertation, extraction A17, A18): 2^D Gauss points per cell instead of
// the centre, and Omega_c = sum of the volumes of the cell's particles instead of the cell volume.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/grid/index_box.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_bins.hpp"
#include "matpoint/particles/particle_set.hpp"
#include "matpoint/shape/mls.hpp"

namespace matpoint {

struct MlsStatistics {
  long evaluations = 0;  // reconstructions at nodes and cell points
  long fallbacks = 0;    // of which fell back to Shepard: singular moment matrix (extraction A16)
};

template <int D>
class MlsMapping {
 public:
  static constexpr int kStress = D * (D + 1) / 2;  // the stress's upper triangle
  static constexpr int kFields = 1 + kStress + D;  // density, stress, body force per unit mass

  explicit MlsMapping(const MlsSpec& spec = {}) : spec_(spec) {}

  /// Bins the particles by cell at their current positions (before each set of transfers).
  void bin(const Grid<D>& grid, const ParticleSet<D>& particles) { bins_.build(grid, particles.x); }
  /// The same for particles that lie in the box `cells` (a decomposed run's near particles).
  void bin(const Grid<D>& grid, const ParticleSet<D>& particles, const IndexBox<D>& cells) {
    bins_.build(grid, particles.x, cells);
  }

  /// A rank of a decomposed run counts the reconstructions at its owned nodes and in its owned
  /// cells only, so that the ranks' counts add up to the serial run's (it evaluates every node and
  /// cell of its window).
  void count_only(const OwnedNodes& nodes, const IndexBox<D>& cells) {
    counted_nodes_ = nodes;
    counted_cells_ = cells;
    count_every_cell_ = false;
  }

  /// p_i = m_i v_i with v_i from (5.15) on the nodes heavier than mass_floor; zero elsewhere.
  void node_momentum(const Grid<D>& grid, const ParticleSet<D>& particles, const std::vector<double>& mass,
                     double mass_floor, std::vector<Vec<D>>& momentum) {
    const auto n = static_cast<std::ptrdiff_t>(grid.node_count);
    const Vec<D> inv_h = grid.h.cwiseInverse();
    long evaluations = 0, fallbacks = 0;
#pragma omp parallel for schedule(static) if (n > 256) reduction(+ : evaluations, fallbacks)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      if (!(mass[i] > mass_floor)) {
        momentum[i].setZero();
        continue;
      }
      const Vec<D> x = grid.node_position(i);
      MlsSums<D, D> sums;
      bins_.for_each_near(x, 2.0, [&](Index p) {  // the cubic weight's support: 2 cells
        const Vec<D> d = (particles.x[p] - x).cwiseProduct(inv_h);
        double w = 1.0;
        for (int a = 0; a < D; ++a) w *= cubic_weight(std::abs(d[a]));
        if (w > 0.0) sums.add(w, d, particles.v[p]);
      });
      Vec<D> v;
      const MlsStatus status = sums.solve(spec_.degree, v);
      if (counted_nodes_.contains(i)) {
        ++evaluations;
        if (status == MlsStatus::Shepard) ++fallbacks;
      }
      momentum[i] = mass[i] * v;
    }
    stats_.evaluations += evaluations;
    stats_.fallbacks += fallbacks;
  }

  /// Nodal mass (5.14) and/or force (5.9) + (5.10) by quadrature over the grid's cells of the MLS
  /// reconstructions (5.16), (5.17); b_c includes the gravity. `body` (optional): b_p per unit mass.
  template <bool Mass, bool Force>
  void cell_quadrature(const Grid<D>& grid, const ParticleSet<D>& particles, const Vec<D>& gravity,
                       const std::vector<Vec<D>>* body, GridFields<D>& fields) {
    reconstruct_at_cell_points(grid, particles, gravity, body);
    const auto n = static_cast<std::ptrdiff_t>(grid.node_count);
    const int q_count = points_per_cell();
    const IndexBox<D> cells = window_cells(grid);
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const auto ijk = grid.node_coords(i);
      double m = 0.0;
      Vec<D> f = Vec<D>::Zero();
      for (int e = 0; e < (1 << D); ++e) {  // the cells with node i as a corner: cell = node - e
        std::array<int, D> cell{};
        for (int a = 0; a < D; ++a) cell[a] = ijk[a] - ((e >> a) & 1);
        if (!cells.contains(cell)) continue;
        const Index local = local_cell(cells, cell);
        for (int q = 0; q < q_count; ++q) {
          const Index k = local * q_count + q;
          double N = 1.0;
          Vec<D> dN = Vec<D>::Ones();
          for (int a = 0; a < D; ++a) {  // bilinear N_i at the point's local coordinate xi
            const bool upper = ((e >> a) & 1) != 0;
            const double xi = local_coordinate(q, a);
            const double phi = upper ? xi : 1.0 - xi, slope = (upper ? 1.0 : -1.0) / grid.h[a];
            for (int b = 0; b < D; ++b) dN[b] *= b == a ? slope : phi;
            N *= phi;
          }
          if constexpr (Mass) m += N * point_mass_[k];
          if constexpr (Force) f += N * point_body_[k] - point_stress_[k] * dN;
        }
      }
      if constexpr (Mass) fields.mass[i] = m;
      if constexpr (Force) fields.force[i] = f;
    }
  }

  [[nodiscard]] const MlsStatistics& statistics() const { return stats_; }

 private:
  /// The cells that the grid's stored nodes touch: every cell of a serial run's grid, the
  /// window's cells on a rank of a decomposed run.
  static IndexBox<D> window_cells(const Grid<D>& grid) {
    IndexBox<D> box;
    for (int a = 0; a < D; ++a)
      box.begin[a] = std::max(0, grid.first[a] - 1),
      box.end[a] = std::min(grid.cells[a], grid.first[a] + grid.nodes[a]);
    return box;
  }
  /// The index of a cell of the box `cells` among the box's cells (x fastest): where its points'
  /// values are.
  static Index local_cell(const IndexBox<D>& cells, const std::array<int, D>& cell) {
    Index n = 0, stride = 1;
    for (int a = 0; a < D; ++a) {
      n += static_cast<Index>(cell[a] - cells.begin[a]) * stride;
      stride *= cells.end[a] - cells.begin[a];
    }
    return n;
  }

  [[nodiscard]] int points_per_cell() const {
    return spec_.quadrature == CellQuadrature::Centre ? 1 : 1 << D;
  }

  /// Local coordinate in [0, 1] along axis a of cell point q: the centre, or the 2-point Gauss rule.
  [[nodiscard]] double local_coordinate(int q, int a) const {
    if (spec_.quadrature == CellQuadrature::Centre) return 0.5;
    constexpr double g = 0.28867513459481287;  // 1 / (2 sqrt 3)
    return ((q >> a) & 1) != 0 ? 0.5 + g : 0.5 - g;
  }

  /// rho_c Omega, sigma_c Omega and rho_c (g + b_c) Omega at every cell point (Omega = Omega_c / points).
  void reconstruct_at_cell_points(const Grid<D>& grid, const ParticleSet<D>& particles, const Vec<D>& gravity,
                                  const std::vector<Vec<D>>* body) {
    const IndexBox<D> box = window_cells(grid);
    const Index cells = box.size();
    const int q_count = points_per_cell();
    point_mass_.resize(cells * q_count);
    point_stress_.resize(cells * q_count);
    point_body_.resize(cells * q_count);
    const Vec<D> inv_h = grid.h.cwiseInverse();
    long evaluations = 0, fallbacks = 0;
    const auto n = static_cast<std::ptrdiff_t>(cells);
#pragma omp parallel for schedule(static) if (n > 256) reduction(+ : evaluations, fallbacks)
    for (std::ptrdiff_t local = 0; local < n; ++local) {
      std::array<int, D> cell{};  // the coordinates of the box's cell `local` (x fastest)
      Index c = 0, stride = 1;    // its flat index in the whole grid
      for (Index rest = local, a = 0; a < D; ++a) {
        const Index extent = box.end[a] - box.begin[a];
        cell[a] = box.begin[a] + static_cast<int>(rest % extent);
        rest /= extent;
        c += cell[a] * stride;
        stride *= grid.cells[a];
      }
      const double omega = cell_volume(grid, particles, c) / q_count;
      const bool counted = count_every_cell_ || counted_cells_.contains(cell);
      Vec<D> corner = grid.origin;  // lowest corner of the cell
      for (int a = 0; a < D; ++a) corner[a] += static_cast<double>(cell[a]) * grid.h[a];
      for (int q = 0; q < q_count; ++q) {
        const Index k = local * q_count + q;
        point_mass_[k] = 0.0;
        point_stress_[k].setZero();
        point_body_[k].setZero();
        if (!(omega > 0.0)) continue;
        Vec<D> x;
        for (int a = 0; a < D; ++a) x[a] = corner[a] + local_coordinate(q, a) * grid.h[a];
        MlsSums<D, kFields> sums;
        bins_.for_each_near(x, 1.5, [&](Index p) {  // the quadratic weight's support: 1.5 cells
          const Vec<D> d = (particles.x[p] - x).cwiseProduct(inv_h);
          double w = 1.0;
          for (int a = 0; a < D; ++a) w *= quadratic_weight(std::abs(d[a]));
          if (w > 0.0) sums.add(w, d, particle_values(particles, body, p));
        });
        typename MlsSums<D, kFields>::Values u;
        const MlsStatus status = sums.solve(spec_.degree, u);
        if (counted) {
          ++evaluations;
          if (status == MlsStatus::Shepard) ++fallbacks;
        }
        if (status == MlsStatus::Empty) continue;
        const double rho = u[0];
        point_mass_[k] = rho * omega;
        int s = 1;
        for (int a = 0; a < D; ++a)
          for (int b = a; b < D; ++b, ++s) point_stress_[k](a, b) = point_stress_[k](b, a) = u[s] * omega;
        point_body_[k] = rho * omega * (gravity + u.template tail<D>());
      }
    }
    stats_.evaluations += evaluations;
    stats_.fallbacks += fallbacks;
  }

  /// Omega_c: the cell volume (eqs. (5.9)-(5.14) as printed), or the summed current volumes of the
  /// particles in the cell (extraction A17, an extension for free surfaces).
  double cell_volume(const Grid<D>& grid, const ParticleSet<D>& particles, Index c) const {
    if (spec_.cell_volume == CellVolume::Full) return grid.cell_volume();
    double v = 0.0;
    bins_.for_each_in_cell(c, [&](Index p) { v += particles.volume(p); });
    return v;
  }

  /// [rho_p, sigma_p (upper triangle), b_p]: rho_p = M_p / V_p.
  static typename MlsSums<D, kFields>::Values particle_values(const ParticleSet<D>& particles,
                                                              const std::vector<Vec<D>>* body, Index p) {
    typename MlsSums<D, kFields>::Values u;
    u[0] = particles.mass[p] / particles.volume(p);
    int s = 1;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b, ++s) u[s] = particles.stress[p](a, b);
    u.template tail<D>() = body != nullptr ? (*body)[p] : Vec<D>::Zero();
    return u;
  }

  MlsSpec spec_;
  ParticleBins<D> bins_;
  MlsStatistics stats_;
  OwnedNodes counted_nodes_;   // every node unless count_only
  IndexBox<D> counted_cells_;  // when count_every_cell_ is false
  bool count_every_cell_ = true;
  std::vector<double> point_mass_;    // rho_c Omega at each cell point of window_cells (x fastest)
  std::vector<Mat<D>> point_stress_;  // sigma_c Omega
  std::vector<Vec<D>> point_body_;    // rho_c (g + b_c) Omega
};

}  // namespace matpoint
