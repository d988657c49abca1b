// Meshfree clouds and shape functions for a set of material points (Iaconeta et al. 2017 §4.2,
// Algorithm 2 step 1; extraction §6.1, §6.4, §6.5): every point gathers the nodes within R of
// itself and evaluates MLS or LME shape functions on that cloud. The robustness repairs of §6.5
// (used by the paper only for the column collapse) are options, and every repair is counted:
//   - MLS: a variable radius R_p = max(R, distance to the min_nodes-th nearest node), so that every
//     cloud holds at least min_nodes nodes (6 in the paper); the dilation grows by R_p / R with it;
//   - LME: when Newton fails or the Hessian's inverse condition number is below the tolerance, the
//     cloud is enlarged by the next-closest node and the functions recomputed, up to max_nodes nodes
//     (30 in the authors' code, extraction §6.5).
// Parameters are multiples of the nodal spacing h (extraction A5): R = 2 sqrt(2) h (the reading
// "twice the cell diagonal" of the paper's "R = 2h2"), MLS R_eff = R / 2, LME beta = gamma / h^2
// with gamma = 1.8.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/shape/meshfree_lme.hpp"
#include "matpoint/shape/meshfree_mls.hpp"
#include "matpoint/shape/meshfree_status.hpp"
#include "matpoint/shape/neighbour_search.hpp"

namespace matpoint {

enum class MeshfreeBasis : std::uint8_t { Mls, Lme };

struct MeshfreeParameters {
  MeshfreeBasis basis = MeshfreeBasis::Mls;
  double spacing = 1.0;                         // h, the nodal spacing of the generating mesh
  double radius_factor = 2.0 * std::sqrt(2.0);  // R / h (extraction A5)
  double dilation_factor = std::sqrt(2.0);      // MLS R_eff / h (R_eff = R / 2, extraction A5)
  MlsWeight mls_weight =
      MlsWeight::Smooth;          // C1 at R, or truncated as in the authors' code (meshfree_mls.hpp)
  double gamma = 1.8;             // LME beta h^2 (eq. (61))
  std::size_t min_nodes = 0;      // MLS repair: at least this many nodes per cloud (0: off)
  std::size_t lme_max_nodes = 0;  // LME repair: augment the cloud up to this size (0: off)
  LmeParameters lme{};            // Newton settings; lme.beta is set from gamma and h

  double radius() const { return radius_factor * spacing; }
  double dilation() const { return dilation_factor * spacing; }
  double beta() const { return gamma / (spacing * spacing); }
};

/// What the repairs of §6.5 did in one evaluation of all points (summed into a run's summary).
struct MeshfreeRepairCounts {
  std::int64_t mls_radius_grown = 0;  // points whose radius was enlarged to reach min_nodes
  std::int64_t mls_shepard = 0;       // points with a singular moment matrix (constant basis)
  std::int64_t lme_augmented = 0;     // points whose cloud was augmented
  std::int64_t lme_nodes_added = 0;   // nodes added by augmentation, over all points
  std::int64_t failed = 0;            // points left without usable functions (status not Ok)
  std::int64_t idle_nodes = 0;        // node-steps in no point's cloud, held (implicit/meshfree)

  MeshfreeRepairCounts& operator+=(const MeshfreeRepairCounts& o) {
    mls_radius_grown += o.mls_radius_grown, mls_shepard += o.mls_shepard;
    lme_augmented += o.lme_augmented, lme_nodes_added += o.lme_nodes_added, failed += o.failed;
    idle_nodes += o.idle_nodes;
    return *this;
  }
};

/// Shape functions of all points in compressed rows: point p's nodes are node[offset[p]] ...
/// node[offset[p + 1] - 1], with values N and gradients dN in the same slots.
template <int D>
struct MeshfreeStencils {
  std::vector<std::int64_t> offset{0};
  std::vector<std::int32_t> node;
  std::vector<double> N;
  std::vector<Vec<D>> dN;
  std::vector<MeshfreeStatus> status;
  MeshfreeRepairCounts repairs;

  std::size_t size() const { return status.size(); }
};

namespace meshfree_detail {

template <int D>
struct Scratch {
  std::vector<NodeDistance> cloud;
  std::vector<Vec<D>> x;
  std::vector<double> N;
  std::vector<Vec<D>> dN;

  void gather(std::span<const Vec<D>> nodes) {
    x.resize(cloud.size()), N.resize(cloud.size()), dN.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) x[i] = nodes[cloud[i].node];
  }
};

/// The variable radius of the MLS repair is this multiple of the distance to the min_nodes-th
/// nearest node with the smooth weight, so that node keeps weight: at 0.8 R_p it is about 4 % of the
/// peak for R = 2 R_eff. The radius R_p = max(R, margin d_k) is continuous in x, as the smooth
/// weight needs. The truncated weight (the authors' code) takes d_k itself.
inline constexpr double kSmoothRadiusMargin = 1.25;

/// MLS at one point, with the variable-radius repair when asked.
template <int D>
MeshfreeStatus mls_point(const Vec<D>& xp, std::span<const Vec<D>> nodes, const NodeCellList<D>& search,
                         const MeshfreeParameters& par, Scratch<D>& s, MeshfreeRepairCounts& counts) {
  const double R = par.radius();
  const double margin = par.mls_weight == MlsWeight::Smooth ? kSmoothRadiusMargin : 1.0 + 1e-9;
  double scale = 1.0;
  s.cloud.clear();
  search.within(xp, R, s.cloud);
  const auto inside = static_cast<std::size_t>(std::count_if(
      s.cloud.begin(), s.cloud.end(), [&](const NodeDistance& c) { return c.distance * margin < R; }));
  if (inside < par.min_nodes && nodes.size() >= par.min_nodes) {
    search.nearest(xp, par.min_nodes, s.cloud);
    const double Rp = s.cloud.back().distance * margin;  // the truncated margin keeps ties with d_k
    s.cloud.clear();
    search.within(xp, Rp, s.cloud);
    scale = Rp / R;
    ++counts.mls_radius_grown;
  }
  s.gather(nodes);
  const auto st =
      mls_shape_functions<D>(xp, s.x, par.dilation() * scale, s.N, s.dN, par.mls_weight, R * scale);
  if (st == MeshfreeStatus::Shepard) ++counts.mls_shepard;
  return st;
}

/// LME at one point, with the node-augmentation repair when asked.
template <int D>
MeshfreeStatus lme_point(const Vec<D>& xp, std::span<const Vec<D>> nodes, const NodeCellList<D>& search,
                         const MeshfreeParameters& par, Scratch<D>& s, MeshfreeRepairCounts& counts) {
  LmeParameters lme = par.lme;
  lme.beta = par.beta();
  s.cloud.clear();
  search.within(xp, par.radius(), s.cloud);
  s.gather(nodes);
  auto outcome = lme_shape_functions<D>(xp, s.x, lme, s.N, s.dN);
  const std::size_t initial = s.cloud.size();
  while (outcome.status != MeshfreeStatus::Ok && s.cloud.size() < par.lme_max_nodes &&
         s.cloud.size() < nodes.size()) {
    search.nearest(xp, s.cloud.size() + 1, s.cloud);  // the old cloud plus the next-closest node
    s.gather(nodes);
    outcome = lme_shape_functions<D>(xp, s.x, lme, s.N, s.dN);
  }
  if (s.cloud.size() > initial) {
    ++counts.lme_augmented;
    counts.lme_nodes_added += static_cast<std::int64_t>(s.cloud.size() - initial);
  }
  return outcome.status;
}

}  // namespace meshfree_detail

namespace meshfree_detail {

/// The points [first, last) into out (appended).
template <int D>
void evaluate_range(std::span<const Vec<D>> points, std::size_t first, std::size_t last,
                    std::span<const Vec<D>> nodes, const NodeCellList<D>& search,
                    const MeshfreeParameters& par, MeshfreeStencils<D>& out) {
  Scratch<D> s;
  for (std::size_t p = first; p < last; ++p) {
    const MeshfreeStatus st = par.basis == MeshfreeBasis::Mls
                                  ? mls_point<D>(points[p], nodes, search, par, s, out.repairs)
                                  : lme_point<D>(points[p], nodes, search, par, s, out.repairs);
    if (st != MeshfreeStatus::Ok && st != MeshfreeStatus::Shepard) ++out.repairs.failed;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      out.node.push_back(s.cloud[i].node);
      out.N.push_back(s.N[i]);
      out.dN.push_back(s.dN[i]);
    }
    out.offset.push_back(static_cast<std::int64_t>(out.node.size()));
    out.status.push_back(st);
  }
}

}  // namespace meshfree_detail

/// Clouds and shape functions of every point (search radius R, basis and repairs from par). The
/// points are split into one contiguous range per thread, each evaluated into its own rows and
/// joined in order, so the result does not depend on the thread count.
template <int D>
void build_meshfree_stencils(std::span<const Vec<D>> points, std::span<const Vec<D>> nodes,
                             const MeshfreeParameters& par, MeshfreeStencils<D>& out) {
  const NodeCellList<D> search(nodes, par.radius());
  int ranges = 1;
#ifdef _OPENMP
  if (static_cast<std::ptrdiff_t>(points.size()) >= kParallelMinimum) ranges = omp_get_max_threads();
#endif
  std::vector<MeshfreeStencils<D>> part(static_cast<std::size_t>(ranges));
  const std::size_t n = points.size();
#pragma omp parallel for schedule(static, 1) if (ranges > 1)
  for (int r = 0; r < ranges; ++r)
    meshfree_detail::evaluate_range<D>(points,
                                       n * static_cast<std::size_t>(r) / static_cast<std::size_t>(ranges),
                                       n * static_cast<std::size_t>(r + 1) / static_cast<std::size_t>(ranges),
                                       nodes, search, par, part[static_cast<std::size_t>(r)]);
  out = std::move(part[0]);
  for (std::size_t r = 1; r < part.size(); ++r) {
    const std::int64_t shift = out.offset.back();
    for (std::size_t k = 1; k < part[r].offset.size(); ++k) out.offset.push_back(part[r].offset[k] + shift);
    out.node.insert(out.node.end(), part[r].node.begin(), part[r].node.end());
    out.N.insert(out.N.end(), part[r].N.begin(), part[r].N.end());
    out.dN.insert(out.dN.end(), part[r].dN.begin(), part[r].dN.end());
    out.status.insert(out.status.end(), part[r].status.begin(), part[r].status.end());
    out.repairs += part[r].repairs;
  }
}

}  // namespace matpoint
