// FMPM(k): grid velocities from a k-term approximation of the full (consistent) mass matrix
// inverse (Nairn 2026; theory in docs/theory/fmpm.md).
//   m~_k^-1 = (I + A + ... + A^{k-1}) m^-1,  A = I - S+S,  S+_ip = M_p S_pi / m_i    eqs. (1)-(2)
//   v+(k) = sum_{l=1..k} dv(l),  dv(1) = m^-1 p+,  dv(l) = A dv(l-1)                 eqs. (5)-(6)
// One pass applies S+S as a gather U_p = sum_j S_pj dv_j followed by a scatter
// sum_p M_p S_pi U_p / m_i: two sweeps over the particle-node pairs instead of Table 1's double
// loop over node pairs, with the step's stencils (no re-evaluation). Each increment then gets
// the corrections of Table 1: blending (§3.3), zeroed velocity-condition directions (line (1),
// Table 2), contact (line (2), set_increment_correction) and the dynamic stop (line (3), §3.4).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "matpoint/explicit/scatter.hpp"
#include "matpoint/grid/velocity_conditions.hpp"
#include "matpoint/io/spec.hpp"

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

template <int D>
class FmpmLoop {
 public:
  explicit FmpmLoop(const FmpmSpec& spec = {}, double measure_floor = 0.0)
      : spec_(spec), measure_floor_(measure_floor) {}

  /// Replaces v (on entry v+(1) = m^-1 p+ with the velocity conditions applied, the first line of
  /// Table 1) by v+(k). `t` is the time of the conditions (used by the "combined" method only).
  /// Returns the order reached (k, or less when the dynamic measure stops the loop).
  template <class Stencils>
  int run(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
          const std::vector<double>& mass, double mass_floor, const VelocityConditions<D>& conditions,
          double t, std::vector<Vec<D>>& v, ScatterWorkspace<D>& ws, Vec<D>* impulse = nullptr,
          double* work = nullptr) {
    const int k = spec_.order;
    statistics_.loops += 1;
    if (k <= 1) return 1;
    const auto start = std::chrono::steady_clock::now();
    const int order = spec_.recursion == FmpmRecursion::Binomial
                          ? run_binomial(grid, stencils, particles, mass, mass_floor, v, ws)
                          : run_incremental(grid, stencils, particles, mass, mass_floor, conditions, t, v, ws,
                                            impulse, work);
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
                        const std::vector<double>& mass, double mass_floor, const std::vector<Vec<D>>& prev,
                        std::vector<Vec<D>>& next, ScatterWorkspace<D>& ws) {
    const auto n = static_cast<std::ptrdiff_t>(particles.size());
    gathered_.resize(particles.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {  // U_p = sum_j S_pj prev_j
      Vec<D> u = Vec<D>::Zero();
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>&) { u += N * prev[node]; });
      gathered_[p] = u;
    }
    if (scratch_.momentum.size() != mass.size()) scratch_.momentum.assign(mass.size(), Vec<D>::Zero());
    scatter_to_grid<kScatterMomentum>(grid, stencils, particles, Vec<D>(Vec<D>::Zero()), scratch_, ws,
                                      &gathered_);
    const auto nodes = static_cast<std::ptrdiff_t>(mass.size());
    next.resize(mass.size());
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
    for (std::ptrdiff_t i = 0; i < nodes; ++i)
      next[i] = mass[i] > mass_floor ? Vec<D>((scratch_.momentum[i] / mass[i]).eval()) : Vec<D>::Zero();
  }

  /// Line (2) of Table 1: a correction of every increment dv(l), l >= 2, after the conditions
  /// (multimaterial contact, explicit/contact.hpp). None by default.
  void set_increment_correction(std::function<void(std::vector<Vec<D>>&)> correction) {
    correction_ = std::move(correction);
  }

  [[nodiscard]] const FmpmStatistics& statistics() const { return statistics_; }
  void restore_statistics(const FmpmStatistics& statistics) { statistics_ = statistics; }
  [[nodiscard]] const FmpmSpec& spec() const { return spec_; }

 private:
  /// Table 1 with lines (1) and (3): dv(l) = A dv(l-1), blended, conditions zeroed, summed.
  template <class Stencils>
  int run_incremental(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                      const std::vector<double>& mass, double mass_floor,
                      const VelocityConditions<D>& conditions, double t, std::vector<Vec<D>>& v,
                      ScatterWorkspace<D>& ws, Vec<D>* impulse, double* work) {
    prev_ = v;  // dv(1) = v+(1); v holds the running sum v* = v+(l)
    const auto nodes = static_cast<std::ptrdiff_t>(v.size());
    for (int l = 2; l <= spec_.order; ++l) {
      apply_projection(grid, stencils, particles, mass, mass_floor, prev_, next_, ws);
      const double scale = blend_scale(l);
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
      for (std::ptrdiff_t i = 0; i < nodes; ++i) prev_[i] = scale * (prev_[i] - next_[i]);  // A dv(l-1)
      if (spec_.boundary_method == FmpmBoundaryMethod::Incremental)
        conditions.zero_constrained(prev_, &mass, impulse, work, t);  // (1), with the walls' work
      if (correction_) correction_(prev_);                            // (2) contact (Net or Evolving)
#pragma omp parallel for schedule(static) if (nodes > kParallelMinimum)
      for (std::ptrdiff_t i = 0; i < nodes; ++i) v[i] += prev_[i];
      if (spec_.measure != FmpmMeasure::None && measure(mass, std::max(mass_floor, measure_floor_), v) < spec_.limit)
        return l;  // (3)
    }
    return spec_.order;
  }

  /// Eq. (4), the original form: v*_1 = k m^-1 p+, v*_l = (k + 1 - l)/l S+S v*_{l-1},
  /// v+(k) = sum_l (-1)^{l+1} v*_l. Kept to verify eq. (6); no per-increment corrections.
  template <class Stencils>
  int run_binomial(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
                   const std::vector<double>& mass, double mass_floor, std::vector<Vec<D>>& v,
                   ScatterWorkspace<D>& ws) {
    const int k = spec_.order;
    const auto nodes = static_cast<std::ptrdiff_t>(v.size());
    prev_.resize(v.size());
    for (std::ptrdiff_t i = 0; i < nodes; ++i) prev_[i] = k * v[i];
    std::vector<Vec<D>>& sum = v;
    for (std::ptrdiff_t i = 0; i < nodes; ++i) sum[i] = prev_[i];
    for (int l = 2; l <= k; ++l) {
      apply_projection(grid, stencils, particles, mass, mass_floor, prev_, next_, ws);
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
  [[nodiscard]] double measure(const std::vector<double>& mass, double mass_floor,
                               const std::vector<Vec<D>>& v) const {
    double change = 0.0, total = 0.0, largest = 0.0;
    long active = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (mass[i] > mass_floor) largest = std::max(largest, v[i].norm());
    const double eps = 0.01 * largest;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!(mass[i] > mass_floor)) continue;
      ++active;
      const double dv = prev_[i].norm(), vi = v[i].norm();
      if (spec_.measure == FmpmMeasure::Means) {
        change += dv;
        total += vi;
      } else if (vi + eps > 0.0) {
        change += dv / (vi + eps);
      }
    }
    if (spec_.measure == FmpmMeasure::Means) return total > 0.0 ? change / total : 0.0;
    return active > 0 ? change / static_cast<double>(active) : 0.0;
  }

  FmpmSpec spec_;
  double measure_floor_ = 0.0;  // nodes at or below it are left out of the dynamic measures
  FmpmStatistics statistics_;
  std::vector<Vec<D>> prev_, next_;  // dv(l - 1) and S+S dv(l - 1)
  std::vector<Vec<D>> gathered_;     // U_p
  GridFields<D> scratch_;            // only its momentum is used
  std::function<void(std::vector<Vec<D>>&)> correction_;
};

}  // namespace matpoint
