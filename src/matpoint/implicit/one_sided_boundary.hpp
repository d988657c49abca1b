// One-sided ("unilateral") mesh boundaries of an implicit run (docs/input.md,
// boundary_conditions[].one_sided): a rigid wall that pushes but never pulls, in contact with the
// body's surface as its particles carry it, not with the mesh's nodes. Each step:
//   1. feet: a particle within about its size of the body's surface (in the reference configuration,
//      from the body's shape) carries material vectors r to the surface points within half its size
//      of its nearest one (surface_feet); a foot is x_f = x_p + F_p r, a point of the deformed
//      surface, and its gap to the wall is
//      g_p = (w - x_f) . n (n the outward normal, w a point of the wall; a foot already past the wall
//      counts as g_p = 0: held where it is, not pushed out in one step). Candidates: the feet within
//      their particle's size plus its normal travel in the step;
//   2. the feet with g_p = 0 are in contact: the stepper adds, per contact foot, the penalty
//      (k/2) (g_p + u~(x_f) . (-n))^2 on the foot's displacement over the step, u~(x_f) = u~(x_p) +
//      grad~ u~(x_p) F_p r_p (the foot moves with its particle; ParticleNewmarkStepper::locate_feet),
//      for non-penetration, and on a no-slip ("fixed") wall (k/2) |P_t u~(x_f)|^2: the material at
//      the foot does not slip (a body rolling on the wall moves its surface points on the wall
//      normal to it, so this does not resist rolling);
//   3. Newton solves the step;
//   4. a contact foot whose spring is stretched (g_p + u~(x_f) . (-n) > 0: the wall would pull) is
//      released, a free candidate whose foot moved past the wall comes into contact, and the step is
//      solved again while the set changes, at most `max_rounds` solves (kMaxOneSidedRounds); then
//      the last solve stands. With the 10 solves allowed before 2026-11-29, a landing's set was still
//      changing after the last one (about half the held feet pulled after each solve, a set more
//      constrained than the field can follow) and the step kept a set in which they pulled the body
//      with penalty forces: the GMM-LME disk of examples/implicit-rolling-disk-incline gained 900 J
//      in the landing step at 0.822 s and 2 300 J by 1 s. Releasing only the feet that pull hardest
//      per solve settled such landings in fewer solves, but a set cut off before it settled then
//      kept feet that pulled, and the T3 disk stuck to the floor for 0.1 s. The set need not settle
//      (a flat face landing flat holds a pressure that alternates from foot to foot), so the last
//      solve is kept rather than the step failed.
// The feet lie on the body's true surface, so a disk meets the wall where its circle does: it rolls
// on the fine polygon of its feet.
// The particles' domains would not do: the lowest row of a lattice of particles is flat over
// 2 sqrt(2 R s) (s the spacing), a facet over which a rolling disk must tip (its centre rose by
// 1.7 mm at h = 0.02 m, R = 0.2 m, and it was thrown off the floor at 0.13 s). Holding the mesh
// node nearest each reaching particle (the rule before 2026-11-28) had the same facets and a pivot:
// the disk rolled 4 % slow whatever h and dt (examples/implicit-rolling-disk-incline/README.md).
// A body must be at least two particles thick where it touches a wall: a particle's foot is on the
// nearest part of the surface, which for a single row may be the far side.
// A plain "fixed" boundary holds every node in both directions, so a disk on it cannot roll: the
// particles behind its contact point would have to lift off nodes that stay put.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint::implicit {

/// Newton solves of a step at most while a one-sided wall's contact set changes (see step 4 above).
inline constexpr int kMaxOneSidedRounds = 30;

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

/// The one-sided walls' penalty over the body's stiffness (lambda + 2 mu) L^(D-2): a foot then
/// penetrates by about 1e-3 of the elastic displacement its load would make (the rolling disk at
/// h = 0.01 m: 2e-8 m per step against a wall the mesh resolves to 1e-2 m). With a million times
/// (tried first) the rolling disk's energy blew up at 0.17 s (h = 0.01 m) and 0.66 s (h = 0.02 m);
/// which part of the step it upset is not known (k times the solves' round-off is a suspect).
inline constexpr double kFootPenalty = 1e3;

/// Whether a reference point lies in a body's shape: (body index, X) -> inside.
template <int D>
using BodyShapeTest = std::function<bool(int, const Vec<D>&)>;

/// The directions searched by nearest_surface_vectors: 72 in 2-D (5 degrees apart), 194 in 3-D (a
/// Fibonacci sphere, about 15 degrees apart).
template <int D>
std::vector<Vec<D>> surface_search_directions() {
  std::vector<Vec<D>> out;
  if constexpr (D == 2) {
    for (int k = 0; k < 72; ++k) {
      const double angle = 2.0 * M_PI * k / 72.0;
      out.push_back(Vec<D>(std::cos(angle), std::sin(angle)));
    }
  } else {
    constexpr int kCount = 194;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < kCount; ++k) {
      const double z = 1.0 - 2.0 * (k + 0.5) / kCount, r = std::sqrt(1.0 - z * z);
      out.push_back(Vec<D>(r * std::cos(golden * k), r * std::sin(golden * k), z));
    }
  }
  return out;
}

/// Where the ray X + t d (t <= range) first leaves body's shape: a march in eighths of the range,
/// then 40 bisections; -1 when it stays inside.
template <int D>
double ray_exit(const BodyShapeTest<D>& inside, int body, const Vec<D>& X, const Vec<D>& d, double range) {
  double inner = 0.0, outer = -1.0;
  for (int k = 1; k <= 8 && outer < 0.0; ++k) {
    const double t = range * k / 8.0;
    (inside(body, X + t * d) ? inner : outer) = t;
  }
  if (outer < 0.0) return -1.0;
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (inner + outer);
    (inside(body, X + mid * d) ? inner : outer) = mid;
  }
  return inner;
}

/// The feet of the particles near their body's surface (step 1): per particle, the reference
/// vectors r to the points where the rays of surface_search_directions() leave the shape, those
/// within half the particle's largest size l of its nearest such point (so that one particle's feet
/// cover l along the surface and its neighbours' overlap): feet about 5 deg x depth apart near the
/// nearest point. One foot per particle (the nearest point alone) would leave the feet l apart: a
/// disk then rocks from foot to foot, hops off one before the next lands and slides while no foot
/// touches (examples/implicit-rolling-disk-incline/README.md: 2.5 % fast at h = 0.02 m, 8 % at
/// 0.04 m). CSR: particle p's feet are vectors[offset[p] .. offset[p + 1]) (none: an interior particle).
template <int D>
struct SurfaceFeet {
  std::vector<std::size_t> offset{0};
  std::vector<Vec<D>> vectors;
};

template <int D>
SurfaceFeet<D> surface_feet(const ParticleSet<D>& particles, const BodyShapeTest<D>& inside) {
  const std::vector<Vec<D>> directions = surface_search_directions<D>();
  std::vector<std::vector<Vec<D>>> per_particle(particles.size());
  const auto count = static_cast<std::ptrdiff_t>(particles.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t q = 0; q < count; ++q) {
    const auto p = static_cast<std::size_t>(q);
    const Vec<D>& X = particles.x0[p];
    const int body = particles.body[p];
    const double size = particles.size0[p].maxCoeff(), range = 1.5 * size;
    std::vector<Vec<D>> exits;
    for (const Vec<D>& d : directions)
      if (const double t = ray_exit(inside, body, X, d, range); t >= 0.0) exits.push_back(t * d);
    if (exits.empty()) continue;
    const Vec<D> nearest = *std::min_element(
        exits.begin(), exits.end(), [](const Vec<D>& a, const Vec<D>& b) { return a.norm() < b.norm(); });
    for (const Vec<D>& r : exits)
      if ((r - nearest).norm() <= 0.5 * size) per_particle[p].push_back(r);
  }
  SurfaceFeet<D> out;
  for (const auto& feet : per_particle) {
    out.vectors.insert(out.vectors.end(), feet.begin(), feet.end());
    out.offset.push_back(out.vectors.size());
  }
  return out;
}

/// Per particle, the reference vector r_p from its reference position x0 to the nearest point of
/// its body's surface: the shortest ray to the outside of the shape among
/// surface_search_directions(), searched to 1.5 times the particle's largest size (a march in
/// eighths, then 40 bisections); NaN where no ray leaves the shape (an interior particle). The
/// length is exact along the directions searched, so it is at most 1/cos(2.5 deg) - 1 = 0.1 % long in
/// 2-D (the ray nearest the normal) and about 1/cos(7.5 deg) - 1 = 0.9 % in 3-D.
template <int D>
std::vector<Vec<D>> nearest_surface_vectors(const ParticleSet<D>& particles, const BodyShapeTest<D>& inside) {
  const SurfaceFeet<D> feet = surface_feet(particles, inside);  // the nearest exit is one of each's feet
  std::vector<Vec<D>> out(particles.size(), Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t p = 0; p < particles.size(); ++p)
    for (std::size_t k = feet.offset[p]; k < feet.offset[p + 1]; ++k)
      if (!std::isfinite(out[p][0]) || feet.vectors[k].norm() < out[p].norm()) out[p] = feet.vectors[k];
  return out;
}

/// A particle near a one-sided wall (step 1): its foot, gap and wall.
template <int D>
struct WallContact {
  std::size_t particle = 0;
  Vec<D> foot = Vec<D>::Zero();
  double gap = 0.0;
  WallPlane plane;
  bool no_slip = true;
  double tolerance = 0.0;  // a stretch (or a pass) smaller than this keeps the foot's state (update)
};

/// A foot's stretch or pass past the wall below this fraction of its particle's size does not change
/// the contact set: it is within the accuracy of the solve (Newton's increment test is 1e-9 relative
/// to the step's displacement), so its sign says nothing about the contact force's.
inline constexpr double kContactTolerance = 1e-8;

/// The displacement over a step of length dt after which a point with Newmark history (v, a) is at
/// rest: Newmark's velocity update (Iaconeta eq. (43), lambda = gamma, zeta = beta),
/// v^(n+1) = gamma/(beta dt) u - (gamma/beta - 1) v - dt (gamma/(2 beta) - 1) a, is zero for
/// u = dt (1 - beta/gamma) v + dt^2 (1/2 - beta/gamma) a. Holding a no-slip foot at u = 0 instead ends
/// the step with v^(n+1) = -(gamma/beta - 1) v - dt (gamma/(2 beta) - 1) a, which for the trapezoidal
/// rule (beta = 1/4, gamma = 1/2) is -v: a landing foot's tangential velocity reflected, not stopped.
template <int D>
Vec<D> newmark_stop_displacement(const Vec<D>& v, const Vec<D>& a, double dt, double beta, double gamma) {
  return dt * (1.0 - beta / gamma) * v + dt * dt * (0.5 - beta / gamma) * a;
}

/// A foot's penalty on the D components of n nodes (local dofs node-major, u_local their values):
/// per held component i (the normal one, and the tangential ones on a no-slip wall), with
/// s_i = sum_J W_J u_(J,i) plus, for the normal one, the gap as a stretch in u's sign (-n_i g) and,
/// for a tangential one, minus the rest displacement t_i (`tangential_rest`, null: 0):
/// r_(J,i) += k W_J s_i and K_(J,i),(L,i) += k W_J W_L (K null: the residual only). The normal
/// spring's stretch along -n is g + s (-n_i); its energy (k/2) (g + s (-n_i))^2. Used by the MPM
/// system (ParticleNewmarkSystem, t = 0) and the meshfree stepper (t = newmark_stop_displacement)
/// alike.
template <int D>
void add_foot_penalty(std::span<const double> W, int normal_axis, double outward, double gap, bool no_slip,
                      double stiffness, const double* u_local, double* r, double* K,
                      const double* tangential_rest = nullptr) {
  const std::size_t n = W.size(), m = n * D;
  for (int i = 0; i < D; ++i) {
    const bool normal = i == normal_axis;
    if (!normal && !no_slip) continue;
    const auto c = static_cast<std::size_t>(i);
    double s = normal ? -outward * gap : (tangential_rest != nullptr ? -tangential_rest[i] : 0.0);
    for (std::size_t J = 0; J < n; ++J) s += W[J] * u_local[J * D + c];
    for (std::size_t J = 0; J < n; ++J) {
      r[J * D + c] += stiffness * W[J] * s;
      if (K != nullptr)
        for (std::size_t L = 0; L < n; ++L) K[(J * D + c) * m + L * D + c] += stiffness * W[J] * W[L];
    }
  }
}

template <int D>
class OneSidedBoundary {
 public:
  OneSidedBoundary() = default;
  using ShapeTest = BodyShapeTest<D>;

  /// The walls of `nodes` (one per distinct plane and kind); `inside` finds the bodies' surfaces
  /// (empty: each particle's domain, an ellipse, stands for the surface).
  explicit OneSidedBoundary(const std::vector<OneSidedNode>& nodes, int max_rounds = kMaxOneSidedRounds,
                            ShapeTest inside = {})
      : max_rounds_(max_rounds), inside_(std::move(inside)) {
    for (const OneSidedNode& node : nodes) {
      const bool known = std::any_of(walls_.begin(), walls_.end(), [&](const Wall& w) {
        return same_plane(w.plane, node.plane) && w.no_slip == node.all_components;
      });
      if (!known) walls_.push_back({node.plane, node.all_components});
    }
  }

  [[nodiscard]] bool empty() const { return walls_.empty(); }
  [[nodiscard]] int max_rounds() const { return max_rounds_; }

  /// Steps 1-2: the candidates of a step of length dt, and which of them are in contact.
  void start_step(const ParticleSet<D>& particles, double dt) {
    if (inside_ && surface_.offset.size() != particles.size() + 1)
      surface_ = surface_feet(particles, inside_);
    candidates_.clear();
    for (std::size_t p = 0; p < particles.size(); ++p)
      for (const Wall& wall : walls_) {
        const WallPlane& plane = wall.plane;
        const double reach = particles.size0[p].maxCoeff() + std::abs(particles.v[p][plane.axis]) * dt;
        const auto add = [&](const Vec<D>& foot) {
          const double gap = std::max(0.0, (plane.position - foot[plane.axis]) * plane.outward);
          if (gap <= reach)
            candidates_.push_back(
                {p, foot, gap, plane, wall.no_slip, kContactTolerance * particles.size0[p].maxCoeff()});
        };
        if (!inside_) {
          add(domain_foot(particles, p, plane));
          continue;
        }
        for (std::size_t k = surface_.offset[p]; k < surface_.offset[p + 1]; ++k)
          add(particles.x[p] + particles.F[p] * surface_.vectors[k]);
      }
    in_contact_.resize(candidates_.size());
    for (std::size_t c = 0; c < candidates_.size(); ++c) in_contact_[c] = candidates_[c].gap <= 0.0 ? 1 : 0;
  }

  [[nodiscard]] const std::vector<WallContact<D>>& candidates() const { return candidates_; }
  [[nodiscard]] const std::vector<char>& in_contact() const { return in_contact_; }

  /// Step 4 after a converged solve: `inward[c]` = u~(x_f) . (-n) of candidate c. A free foot past
  /// the wall comes into contact, a held foot whose spring is stretched (the wall would pull) is
  /// released; changes within the candidate's tolerance do not count. Returns whether the contact
  /// set changed (the step must be solved again).
  bool update(const std::vector<double>& inward) {
    bool changed = false;
    for (std::size_t c = 0; c < candidates_.size(); ++c) {
      const double stretch = candidates_[c].gap + inward[c], tolerance = candidates_[c].tolerance;
      const bool contact = in_contact_[c] != 0 ? stretch <= tolerance : stretch < -tolerance;
      changed = changed || contact != static_cast<bool>(in_contact_[c]);
      in_contact_[c] = static_cast<char>(contact);
    }
    return changed;
  }

 private:
  /// Without shapes, particle p's foot is the point of its domain, taken as the ellipse (ellipsoid)
  /// F diag(l / 2) xi, |xi| <= 1, farthest along the wall's outward normal (its extent does not
  /// change when the particle rotates, as a box's would).
  static Vec<D> domain_foot(const ParticleSet<D>& particles, std::size_t p, const WallPlane& plane) {
    const Vec<D> n = plane.outward * Vec<D>::Unit(plane.axis);
    const Vec<D> half = 0.5 * particles.size0[p];
    const Vec<D> scaled = half.cwiseProduct(particles.F[p].transpose() * n);  // diag(l/2) F^T n
    const double norm = scaled.norm();
    return norm > 0.0 ? Vec<D>(particles.x[p] + particles.F[p] * half.cwiseProduct(scaled) / norm)
                      : particles.x[p];
  }

  struct Wall {
    WallPlane plane;
    bool no_slip = true;
  };
  static bool same_plane(const WallPlane& a, const WallPlane& b) {
    return a.axis == b.axis && a.position == b.position && a.outward == b.outward;
  }

  std::vector<Wall> walls_;
  int max_rounds_ = kMaxOneSidedRounds;
  ShapeTest inside_;
  SurfaceFeet<D> surface_;  // the particles' feet (with shapes)
  std::vector<WallContact<D>> candidates_;
  std::vector<char> in_contact_;
};

}  // namespace matpoint::implicit
