// FMPM(k): grid velocities from a k-term approximation of the full (consistent) mass matrix
// inverse (Nairn 2026; theory in docs/theory/fmpm.md).
//   m~_k^-1 = (I + A + ... + A^{k-1}) m^-1,  A = I - S+S,  S+_ip = M_p S_pi / m_i    eqs. (1)-(2)
//   v+(k) = sum_{l=1..k} dv(l),  dv(1) = m^-1 p+,  dv(l) = A dv(l-1)                 eqs. (5)-(6)
// One pass applies S+S as a gather U_p = sum_j S_pj dv_j followed by a scatter
// sum_p M_p S_pi U_p / m_i: two sweeps over the particle-node pairs instead of Table 1's double
// loop over node pairs, with the step's stencils (no re-evaluation). Each increment then gets
// the corrections of Table 1: blending (§3.3), zeroed velocity-condition directions (line (1),
// Table 2), contact (line (2), set_increment_correction) and the dynamic stop (line (3), §3.4).
// Transport FMPM (Nairn 2026 §3.5, extraction §2.6): the same loop with Value = double serves a
// transported scalar (temperature), the nodal capacity in place of the nodal mass and the
// particle weights M_p C_V,p (set_particle_weights) in place of M_p; its Conditions are then the
// thermal ones (grid/thermal_conditions.hpp) and its "impulse" the heat they add.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <type_traits>
#include <utility>
#include <vector>

#include "matpoint/core/exact_sum.hpp"
#include "matpoint/explicit/scalar_scatter.hpp"
#include "matpoint/explicit/scatter.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/grid/velocity_conditions.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/parallel/communicator.hpp"

namespace matpoint {

/// Counts of a run's FMPM loops (dynamic FMPM reports the average order reached).
struct FmpmStatistics {
  long loops = 0;
  long passes = 0;       // sum over loops of (order reached - 1)
  double seconds = 0.0;  // wall time inside the loops
  [[nodiscard]] double average_order() const {
    return loops > 0 ? 1.0 + static_cast<double>(passes) / static_cast<double>(loops) : 0.0;
  }
};

/// |x| of a transported value: the Euclidean norm of a velocity, the magnitude of a scalar.
template <int D>
double magnitude(const Vec<D>& x) {
  return x.norm();
}
inline double magnitude(double x) { return std::abs(x); }

/// Value: Vec<D> (mechanics: velocities, nodal masses) or double (transport: e.g. temperatures,
/// nodal capacities).
template <int D, class Value = Vec<D>>
class FmpmLoop {
  static constexpr bool kScalar = std::is_same_v<Value, double>;

 public:
  explicit FmpmLoop(const FmpmSpec& spec = {}, double measure_floor = 0.0)
      : spec_(spec), measure_floor_(measure_floor) {}

  /// Replaces v (on entry v+(1) = m^-1 p+ with the velocity conditions applied, the first line of
  /// Table 1) by v+(k). `t` is the time of the conditions (used by the "combined" method only).
  /// Returns the order reached (k, or less when the dynamic measure stops the loop).
  /// `mass`: the nodal masses (capacities in transport); `conditions`: VelocityConditions<D>, or
  /// the transport's conditions with the same zero_constrained/apply interface.
  template <class Stencils, class Conditions>
  int run(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
          const std::vector<double>& mass, double mass_floor, const Conditions& conditions, double t,
          std::vector<Value>& v, Value* impulse = nullptr, double* work = nullptr) {
    const int k = spec_.order;
    statistics_.loops += 1;
    if (k <= 1) return 1;
    const auto start = std::chrono::steady_clock::now();
    const int order =
        spec_.recursion == FmpmRecursion::Binomial
            ? run_binomial(grid, stencils, particles, mass, mass_floor, v)
            : run_incremental(grid, stencils, particles, mass, mass_floor, conditions, t, v, impulse, work);
    if (spec_.boundary_method == FmpmBoundaryMethod::Combined || spec_.recursion == FmpmRecursion::Binomial) {
      double ignored_work = 0.0;  // Nairn 2026 §3.1 "combined": overwrite v+(k) on the condition nodes
      conditions.apply(v, t, impulse ? &mass : nullptr, impulse, work ? work : &ignored_work);
    }
    statistics_.passes += order - 1;
    statistics_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return order;
  }

  /// next = S+S prev on the active nodes (zero on the others): one FMPM pass.
  template <class Stencils>
  void apply_projection(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                        const std::vector<double>& mass, double mass_floor, const std::vector<Value>& prev,
                        std::vector<Value>& next) {
    const auto n = static_cast<std::ptrdiff_t>(particles.size());
    gathered_.resize(particles.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {  // U_p = sum_j S_pj prev_j
      Value u = zero();
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>&) { u += N * prev[node]; });
      gathered_[p] = u;
    }
    const std::vector<Value>& weighted = scatter_weighted(grid, stencils, particles);  // w_p S_pi U_p
    const auto nodes = static_cast<std::ptrdiff_t>(mass.size());
    next.resize(mass.size());
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
    for (std::ptrdiff_t i = 0; i < nodes; ++i)
      next[i] = mass[i] > mass_floor ? Value(weighted[i] / mass[i]) : zero();
  }

  /// Transport: the particle weights w_p (M_p C_V,p) that play the particle masses' part.
  void set_particle_weights(const std::vector<double>* weights) { weights_ = weights; }

  /// Line (2) of Table 1: a correction of every increment dv(l), l >= 2, after the conditions
  /// (multimaterial contact, explicit/contact.hpp). None by default.
  void set_increment_correction(std::function<void(std::vector<Value>&)> correction) {
    correction_ = std::move(correction);
  }

  /// A decomposed run: the dynamic measures count the grid nodes `owned` (of `field_nodes`, in
  /// every field) this rank owns and add up over `comm`'s ranks, exactly (measure()).
  void decompose(const Communicator& comm, OwnedNodes owned, Index field_nodes) {
    comm_ = comm;
    owned_ = std::move(owned), field_nodes_ = field_nodes;
  }

  [[nodiscard]] const FmpmStatistics& statistics() const { return statistics_; }
  void restore_statistics(const FmpmStatistics& statistics) { statistics_ = statistics; }
  [[nodiscard]] const FmpmSpec& spec() const { return spec_; }

 private:
  static Value zero() {
    if constexpr (kScalar)
      return 0.0;
    else
      return Vec<D>::Zero();
  }

  /// sum_p w_p S_pi U_p: the masses M_p (mechanics, through scatter_to_grid) or the weights.
  template <class Stencils>
  const std::vector<Value>& scatter_weighted(const Grid<D>& grid, const Stencils& stencils,
                                             const ParticleSet<D>& particles) {
    if constexpr (kScalar) {
      const std::vector<double>& w = *weights_;
      scatter_scalar(grid, stencils, scratch_,
                     [&](std::ptrdiff_t p, double N, const Vec<D>&) { return w[p] * N * gathered_[p]; });
      return scratch_;
    } else {
      if (scratch_.momentum.size() != static_cast<std::size_t>(grid.node_count))
        scratch_.momentum.assign(grid.node_count, Vec<D>::Zero());
      scatter_to_grid<kScatterMomentum>(grid, stencils, particles, Vec<D>(Vec<D>::Zero()), scratch_,
                                        &gathered_);
      return scratch_.momentum;
    }
  }

  /// Table 1 with lines (1) and (3): dv(l) = A dv(l-1), blended, conditions zeroed, summed.
  template <class Stencils, class Conditions>
  int run_incremental(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                      const std::vector<double>& mass, double mass_floor, const Conditions& conditions,
                      double t, std::vector<Value>& v, Value* impulse, double* work) {
    prev_ = v;  // dv(1) = v+(1); v holds the running sum v* = v+(l)
    const auto nodes = static_cast<std::ptrdiff_t>(v.size());
    for (int l = 2; l <= spec_.order; ++l) {
      apply_projection(grid, stencils, particles, mass, mass_floor, prev_, next_);
      const double scale = blend_scale(l);
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
      for (std::ptrdiff_t i = 0; i < nodes; ++i) prev_[i] = scale * (prev_[i] - next_[i]);  // A dv(l-1)
      if (spec_.boundary_method == FmpmBoundaryMethod::Incremental)
        conditions.zero_constrained(prev_, &mass, impulse, work, t);  // (1), with the walls' work
      if (correction_) correction_(prev_);                            // (2) contact (Net or Evolving)
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
      for (std::ptrdiff_t i = 0; i < nodes; ++i) v[i] += prev_[i];
      if (spec_.measure != FmpmMeasure::None &&
          measure(mass, std::max(mass_floor, measure_floor_), v) < spec_.limit)
        return l;  // (3)
    }
    return spec_.order;
  }

  /// Eq. (4), the original form: v*_1 = k m^-1 p+, v*_l = (k + 1 - l)/l S+S v*_{l-1},
  /// v+(k) = sum_l (-1)^{l+1} v*_l. Kept to verify eq. (6); no per-increment corrections.
  template <class Stencils>
  int run_binomial(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                   const std::vector<double>& mass, double mass_floor, std::vector<Value>& v) {
    const int k = spec_.order;
    const auto nodes = static_cast<std::ptrdiff_t>(v.size());
    prev_.resize(v.size());
    for (std::ptrdiff_t i = 0; i < nodes; ++i) prev_[i] = k * v[i];
    std::vector<Value>& sum = v;
    for (std::ptrdiff_t i = 0; i < nodes; ++i) sum[i] = prev_[i];
    for (int l = 2; l <= k; ++l) {
      apply_projection(grid, stencils, particles, mass, mass_floor, prev_, next_);
      const double factor = static_cast<double>(k + 1 - l) / l;
      const double sign = l % 2 == 0 ? -1.0 : 1.0;
      for (std::ptrdiff_t i = 0; i < nodes; ++i) {
        prev_[i] = factor * next_[i];
        sum[i] += sign * prev_[i];
      }
    }
    return k;
  }

  /// Blending with FMPM(m) (Nairn 2026 §3.3): dv(l) is scaled by alpha_b when l mod m = 1 or m = 1.
  [[nodiscard]] double blend_scale(int l) const {
    const int m = spec_.blend_with;
    if (m <= 0) return 1.0;
    return (m == 1 || l % m == 1) ? spec_.blend_factor : 1.0;
  }

  /// Dynamic FMPM measures of §3.4 over the active nodes, after the corrections:
  ///   Means   = sum |dv_i| / sum |v*_i|
  ///   Changes = mean over nodes of |dv_i| / (|v*_i| + eps), eps = 1 % of max |v*_i|.
  /// The sums are exact (core/exact_sum.hpp), rounded once each: a decomposed run adds its
  /// ranks' owned nodes and gets the serial run's measure to the bit, so every rank stops the
  /// loop where the serial run does (docs/scale-out.md §17 stage 3).
  [[nodiscard]] double measure(const std::vector<double>& mass, double mass_floor,
                               const std::vector<Value>& v) const {
    ExactSum change, total;
    double largest = 0.0;
    long active = 0;
    const auto counted = [&](std::size_t i) {
      if (!(mass[i] > mass_floor)) return false;
      if (field_nodes_ == 0) return true;  // one rank: every node
      const Index node = static_cast<Index>(i) % field_nodes_;
      return owned_.contains(node);
    };
    for (std::size_t i = 0; i < v.size(); ++i)
      if (counted(i)) largest = std::max(largest, magnitude(v[i]));
    if (comm_.distributed()) largest = comm_.max(largest);
    const double eps = 0.01 * largest;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!counted(i)) continue;
      ++active;
      const double dv = magnitude(prev_[i]), vi = magnitude(v[i]);
      if (spec_.measure == FmpmMeasure::Means) {
        change.add(dv);
        total.add(vi);
      } else if (vi + eps > 0.0) {
        change.add(dv / (vi + eps));
      }
    }
    change.sum_over(comm_);
    if (spec_.measure == FmpmMeasure::Means) {
      total.sum_over(comm_);
      return total.value() > 0.0 ? change.value() / total.value() : 0.0;
    }
    if (comm_.distributed()) active = comm_.sum(active);
    return active > 0 ? change.value() / static_cast<double>(active) : 0.0;
  }

  FmpmSpec spec_;
  double measure_floor_ = 0.0;  // nodes at or below it are left out of the dynamic measures
  FmpmStatistics statistics_;
  std::vector<Value> prev_, next_;  // dv(l - 1) and S+S dv(l - 1)
  std::vector<Value> gathered_;     // U_p
  // mechanics: only the momentum is used; transport: the weighted sum itself
  std::conditional_t<kScalar, std::vector<double>, GridFields<D>> scratch_;
  const std::vector<double>* weights_ = nullptr;  // transport: w_p
  std::function<void(std::vector<Value>&)> correction_;
  Communicator comm_;  // a decomposed run's ranks (decompose()); one rank by default
  OwnedNodes owned_;
  Index field_nodes_ = 0;  // 0: every node counts
};

}  // namespace matpoint
