// Checkerboard (hourglass) content of the grid velocity: the mode that one-point cell quadrature
// does not see (Gong 2015 extraction A18, smoke test S4). With s_i = (-1)^(i+j+k) of node i:
//   checkerboard velocity  |sum_i m_i s_i v_i| / sum_i m_i                      (S4's measure)
//   grid rms velocity      sqrt(sum_i m_i |v_i|^2 / sum_i m_i)
//   hourglass energy       1/2 sum_c m_c |g_c|^2,  g_c = 2^-D sum_{corners k} s_k v_k,  m_c = 2^-D sum_k m_k
// (g_c is the coefficient of the bilinear xi*eta term of cell c: zero strain at the cell centre).
// With multimaterial contact the arrays hold one block of N nodes per field; the sums run over all
// of them (each field's checkerboard and hourglass modes count).
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/parallel/communicator.hpp"

namespace matpoint {

struct GridModes {
  double checkerboard_velocity = 0.0, rms_velocity = 0.0, hourglass_energy = 0.0;
};

/// The nodes a rank counts in a decomposed run (a node near a rank boundary is stored by two
/// ranks with the same values): those it owns (Simulation::owned_nodes), and the ranks to sum
/// over. The default: one rank that owns every node.
struct NodeOwnership {
  Communicator comm;
  OwnedNodes owned;
  [[nodiscard]] bool owns(Index node) const { return owned.contains(node); }
};

/// Every rank calls it in a decomposed run (a collective): the sums run over the owned nodes (a
/// cell counts on the rank that owns its lowest node, which must hold complete values on the
/// cell's other corners) and are added over the ranks, so every rank gets the same modes.
template <int D>
GridModes measure_grid_modes(const Grid<D>& grid, const std::vector<double>& mass,
                             const std::vector<Vec<D>>& velocity, const NodeOwnership& owned = {}) {
  GridModes g;
  auto sign = [&](const std::array<int, D>& ijk) {
    int sum = 0;
    for (int a = 0; a < D; ++a) sum += ijk[a];
    return (sum % 2 + 2) % 2 == 0 ? 1.0 : -1.0;
  };
  const Index n = grid.node_count;
  const Index fields = static_cast<Index>(mass.size()) / n;
  // This rank's raw sums: sum m, sum m |v|^2, sum s m v (D), the hourglass energy.
  std::vector<double> sums(3 + D, 0.0);
  double& total = sums[0];
  double& energy = sums[1];
  Vec<D> checker = Vec<D>::Zero();
  for (Index i = 0; i < fields * n; ++i) {
    if (!owned.owns(i % n)) continue;
    total += mass[i];
    energy += mass[i] * velocity[i].squaredNorm();
    checker += sign(grid.node_coords(i % n)) * mass[i] * velocity[i];
  }
  double hourglass = 0.0;
  for (Index f = 0; f < fields; ++f)
    for (Index i = 0; i < n; ++i) {  // cells by their lowest node
      if (!owned.owns(i)) continue;
      const auto ijk = grid.node_coords(i);
      bool interior = true;
      for (int a = 0; a < D; ++a) interior = interior && ijk[a] + 1 < grid.first[a] + grid.nodes[a];
      if (!interior) continue;
      double m = 0.0;
      Vec<D> hg = Vec<D>::Zero();
      for (int e = 0; e < (1 << D); ++e) {
        std::array<int, D> corner = ijk;
        for (int a = 0; a < D; ++a) corner[a] += (e >> a) & 1;
        const Index k = f * n + grid.node_index(corner);
        m += mass[k];
        hg += sign(corner) * velocity[k];
      }
      const double scale = 1.0 / (1 << D);
      hourglass += 0.5 * (m * scale) * (hg * scale).squaredNorm();
    }
  for (int a = 0; a < D; ++a) sums[2 + a] = checker[a];
  sums[2 + D] = hourglass;
  owned.comm.sum(sums);  // rank order: the same bits on every rank; one rank: unchanged
  if (!(total > 0.0)) return g;
  for (int a = 0; a < D; ++a) checker[a] = sums[2 + a];
  g.checkerboard_velocity = checker.norm() / total;
  g.rms_velocity = std::sqrt(energy / total);
  g.hourglass_energy = sums[2 + D];
  return g;
}

}  // namespace matpoint
