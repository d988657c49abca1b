// One-sided ("unilateral") mesh boundaries of an implicit run (docs/input.md,
// boundary_conditions[].one_sided): a rigid wall that pushes but never pulls. Each step the wall
// holds (fixed: every component, slip: the normal one) only the nodes where the body touches it,
// and among those only the nodes it pushes:
//   1. touched, on the step-start positions: for each particle whose deformed domain reaches the
//      wall, the wall's node nearest to the particle's projection on it. A rolling disk's contact
//      point is then held by the node nearest to it. Holding every node under the body's bottom row
//      of cells instead makes nodes ahead of the contact point pivots about which the disk must
//      climb (a / (2/3 g sin theta) = 0.74, 0.87, 0.92 at R / h = 5, 10, 20 on the incline), and the
//      explicit solver's rule, a node covered by a reaching particle's own domain
//      (explicit/face_contact.hpp), leaves the contact free in more than half of the steps with three
//      particles per triangle, whose domains (0.41 h wide) do not tile the floor: the disk partly
//      slides (1.04 and 1.09 at R / h = 5 and 20; examples/implicit-rolling-disk-incline/README.md);
//   2. Newton solves the step with the touching nodes held;
//   3. a held node whose reaction pulls the body towards the wall's outside is released, a free
//      touching node that moved into the wall is held, and the step is solved again while the set
//      changes (at most `max_rounds` solves).
// A plain "fixed" boundary holds every node in both directions, so a disk on it cannot roll: the
// particles behind its contact point would have to lift off nodes that stay put.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint::implicit {

/// The plane of a one-sided boundary: x_axis = position, the body on the side opposite `outward`.
struct WallPlane {
  int axis = 0;
  double position = 0.0;
  double outward = -1.0;  // -1: the wall is at the mesh's smallest coordinate; +1: its largest
};

/// The plane through `nodes` if they all share one coordinate and that coordinate is the mesh's
/// smallest or largest along its axis; none otherwise (a curved or interior boundary).
template <int D>
std::optional<WallPlane> wall_plane(const std::vector<Vec<D>>& mesh_nodes, const std::vector<Index>& nodes) {
  if (nodes.empty()) return std::nullopt;
  for (int a = 0; a < D; ++a) {
    double lo = mesh_nodes[static_cast<std::size_t>(nodes.front())][a], hi = lo;
    for (Index n : nodes) {
      const double x = mesh_nodes[static_cast<std::size_t>(n)][a];
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    double mesh_lo = lo, mesh_hi = hi;
    for (const auto& x : mesh_nodes) mesh_lo = std::min(mesh_lo, x[a]), mesh_hi = std::max(mesh_hi, x[a]);
    const double tolerance = 1e-10 * (mesh_hi - mesh_lo);
    if (hi - lo > tolerance) continue;
    if (lo - mesh_lo <= tolerance) return WallPlane{a, lo, -1.0};
    if (mesh_hi - hi <= tolerance) return WallPlane{a, hi, 1.0};
    return std::nullopt;
  }
  return std::nullopt;
}

/// A node of a one-sided boundary: its plane and whether the wall holds every component (fixed,
/// no slip) or only the normal one (slip).
struct OneSidedNode {
  Index node = 0;
  WallPlane plane;
  bool all_components = true;
};

template <int D>
class OneSidedBoundary {
 public:
  OneSidedBoundary() = default;
  explicit OneSidedBoundary(std::vector<OneSidedNode> nodes, int max_rounds = 10)
      : nodes_(std::move(nodes)), max_rounds_(max_rounds) {
    for (std::size_t first = 0; first < nodes_.size();) {  // the walls: runs of nodes on one plane
      std::size_t last = first + 1;
      while (last < nodes_.size() && same_plane(nodes_[last].plane, nodes_[first].plane)) ++last;
      walls_.emplace_back(first, last);
      first = last;
    }
  }

  [[nodiscard]] bool empty() const { return nodes_.empty(); }
  [[nodiscard]] int max_rounds() const { return max_rounds_; }

  /// Step 1: the touched nodes, held at the start of the step's first solve: for each particle whose
  /// deformed domain reaches a wall, the wall's node nearest to the particle's projection on it.
  void start_step(const std::vector<Vec<D>>& mesh_nodes, const ParticleSet<D>& particles) {
    touching_.assign(nodes_.size(), 0);
    for (std::size_t p = 0; p < particles.size(); ++p) {
      const Vec<D>& x = particles.x[p];
      for (const auto& [first, last] : walls_) {
        const WallPlane& plane = nodes_[first].plane;
        const double reach =
            x[plane.axis] + plane.outward * particles.half_extent(p, Vec<D>::Unit(plane.axis));
        if ((reach - plane.position) * plane.outward >= 0.0)
          touching_[nearest(mesh_nodes, x, first, last)] = 1;
      }
    }
    held_ = touching_;
  }

  /// The Dirichlet flags of this round: `base` (every condition's dofs) with the one-sided dofs set
  /// as held_ says.
  [[nodiscard]] std::vector<char> dirichlet(const std::vector<char>& base) const {
    std::vector<char> flags = base;
    for (std::size_t k = 0; k < nodes_.size(); ++k)
      for (int a = 0; a < D; ++a)
        if (nodes_[k].all_components || a == nodes_[k].plane.axis)
          flags[static_cast<std::size_t>(nodes_[k].node * D + a)] = held_[k];
    return flags;
  }

  /// Step 3 after a converged solve u with the unconstrained residual `reaction` (the force the
  /// wall must add at each held dof, eq. K u = -R's constraint force): returns whether the held set
  /// changed, i.e. whether the step must be solved again.
  bool update(const Eigen::VectorXd& u, const Eigen::VectorXd& reaction) {
    bool changed = false;
    for (std::size_t k = 0; k < nodes_.size(); ++k) {
      const auto dof = static_cast<Eigen::Index>(nodes_[k].node * D + nodes_[k].plane.axis);
      const double outward = nodes_[k].plane.outward;
      // held: the wall's force must point inward (push); free: the node must not enter the wall
      const bool hold = held_[k] ? reaction[dof] * outward <= 0.0 : touching_[k] && u[dof] * outward > 0.0;
      changed = changed || hold != static_cast<bool>(held_[k]);
      held_[k] = static_cast<char>(hold);
    }
    return changed;
  }

 private:
  static bool same_plane(const WallPlane& a, const WallPlane& b) {
    return a.axis == b.axis && a.position == b.position && a.outward == b.outward;
  }
  /// The node of nodes_[first, last) (one wall) nearest to x along the wall.
  std::size_t nearest(const std::vector<Vec<D>>& mesh_nodes, const Vec<D>& x, std::size_t first,
                      std::size_t last) const {
    const int axis = nodes_[first].plane.axis;
    std::size_t best = first;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = first; k < last; ++k) {
      Vec<D> offset = mesh_nodes[static_cast<std::size_t>(nodes_[k].node)] - x;
      offset[axis] = 0.0;
      if (const double d = offset.squaredNorm(); d < best_distance) best = k, best_distance = d;
    }
    return best;
  }

  std::vector<OneSidedNode> nodes_;
  std::vector<std::pair<std::size_t, std::size_t>> walls_;  // [first, last) of nodes_ on one plane
  int max_rounds_ = 10;
  std::vector<char> touching_, held_;
};

}  // namespace matpoint::implicit
