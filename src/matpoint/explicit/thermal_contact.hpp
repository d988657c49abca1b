// Heat across contact surfaces in coupled conduction (docs/theory/heat.md, "Contact"). With
// multi-field contact (contact.hpp) every field has its own nodal temperature; at the nodes where
// the mechanics finds fields in contact (stick: every shared node; the other laws: where the
// fields touch) the fields exchange heat by one of
//   perfect:      one temperature per node, T_i = sum_f c_f T_f / sum_f c_f, on T_i, on T+_i and on
//                 every FMPM(k) increment (the single nodal temperature of NairnMPM's conduction,
//                 which reproduces one body's conduction when the fields are one material);
//   conductance:  the flux h_c A_i (T_b - T_a) from b to a, with the nodal contact area
//                 A_i = |g_a - g_b| / 2, g_f = sum_p V_p grad S_pi over field f's particles. By the
//                 divergence theorem g_f,i is the outward surface integral of S_i over field f's
//                 boundary, so on the interface (n_b = -n_a) the two add up, A_i = int S_i dA there,
//                 and the A_i of a flat interface sum to its area, while the free surfaces the two
//                 fields share at the node (a common face of the grid) cancel. The two-node exchange
//                 c_a dT_a/dt = -c_b dT_b/dt = h_c A (T_b - T_a) is integrated exactly over the step,
//                 Q = (T_b - T_a) (1 - exp(-h_c A (1/c_a + 1/c_b) dt)) / (1/c_a + 1/c_b),
//                 unconditionally stable and tending to perfect contact as h_c grows;
//   insulated:    no exchange.
// A node of three or more fields: perfect contact mixes all of them; with a conductance each field
// exchanges with the others pooled (capacity-weighted, g_pool their sum) on |g_a - g_pool| / 4,
// half the area (each interface is then seen from both sides). Fields without capacity (a rigid material
// without C_V) take no part.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "matpoint/explicit/contact.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
class ThermalContactCoupling {
 public:
  ThermalContactCoupling() = default;
  ThermalContactCoupling(ThermalContact mode, double conductance) : mode_(mode), conductance_(conductance) {}

  [[nodiscard]] bool perfect() const { return mode_ == ThermalContact::Perfect && !members_.empty(); }

  /// This step's contact nodes from the mechanics' detection; only fields with capacity above
  /// `floor` take part.
  void prepare(const MultiFieldContact<D>& contact, const std::vector<double>& capacity, double floor) {
    members_.clear();
    start_.clear();
    pairs_.clear();
    if (mode_ == ThermalContact::Insulated || contact.contact_nodes() == 0) return;
    const Index nodes = contact.field_nodes();
    field_nodes_ = nodes;
    fields_ = contact.fields();
    const auto has = [&](int f, Index node) { return capacity[f * nodes + node] > floor; };
    if (mode_ == ThermalContact::Perfect) {
      scratch_.clear();
      contact.for_each_contact([&](Index node, int a, int b, bool in_contact) {
        if (!in_contact) return;
        for (int f = 0; f < contact.fields(); ++f)  // b < 0: a against all the others
          if ((f == a || f == b || (b < 0 && f != a)) && has(f, node)) scratch_.emplace_back(node, f);
      });
      group(nodes);
      return;
    }
    contact.for_each_contact([&](Index node, int a, int b, bool in_contact) {
      if (in_contact && has(a, node) && (b < 0 || has(b, node))) pairs_.push_back({node, a, b});
    });
  }

  /// Perfect contact: the capacity-weighted mean of `value` (temperatures or their increments)
  /// on every contact node.
  void mix(std::vector<double>& value, const std::vector<double>& capacity) const {
    for (std::size_t g = 0; g + 1 < start_.size(); ++g) {
      double heat = 0.0, total = 0.0;
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
        heat += capacity[members_[k]] * value[members_[k]];
        total += capacity[members_[k]];
      }
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) value[members_[k]] = heat / total;
    }
  }

  /// Conductance: adds each contact's exact two-node exchange over dt, as a mean heat flow (W),
  /// to `flow`.
  template <class Stencils>
  void exchange(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& ps,
                const std::vector<double>& T, const std::vector<double>& capacity, double floor, double dt,
                std::vector<double>& flow) {
    if (pairs_.empty()) return;
    const Index field_nodes = field_nodes_;
    const int fields = fields_;
    volume_gradients(grid, stencils, ps);
    for (const auto& c : pairs_) {
      const Index ia = c.a * field_nodes + c.node;
      if (c.b >= 0) {
        const Index ib = c.b * field_nodes + c.node;
        const double area = 0.5 * (gradient_[ia] - gradient_[ib]).norm();
        const double Q = exchanged(T[ib] - T[ia], capacity[ia], capacity[ib], area, dt);
        flow[ia] += Q / dt;
        flow[ib] -= Q / dt;
        continue;
      }
      double pool = 0.0, pool_heat = 0.0;  // the other fields at the node, pooled
      Vec<D> pool_gradient = Vec<D>::Zero();
      for (int g = 0; g < fields; ++g) {
        const Index ig = g * field_nodes + c.node;
        if (g == c.a || !(capacity[ig] > floor)) continue;
        pool += capacity[ig];
        pool_heat += capacity[ig] * T[ig];
        pool_gradient += gradient_[ig];
      }
      if (!(pool > 0.0)) continue;
      const double area = 0.25 * (gradient_[ia] - pool_gradient).norm();
      const double Q = exchanged(pool_heat / pool - T[ia], capacity[ia], pool, area, dt);
      flow[ia] += Q / dt;
      for (int g = 0; g < fields; ++g) {
        const Index ig = g * field_nodes + c.node;
        if (g != c.a && capacity[ig] > floor) flow[ig] -= (Q / dt) * capacity[ig] / pool;
      }
    }
  }

 private:
  struct Pair {
    Index node;
    int a, b;  // b = -1: a against the other fields pooled
  };

  /// Heat from b to a over dt: c_a dT_a/dt = h A (T_b - T_a) = -c_b dT_b/dt, integrated exactly.
  [[nodiscard]] double exchanged(double difference, double ca, double cb, double area, double dt) const {
    const double inverse = 1.0 / ca + 1.0 / cb;
    return difference * -std::expm1(-conductance_ * area * inverse * dt) / inverse;
  }

  /// scratch_ (node, field) -> members_ grouped by node (multi-field indices), groups of two or more.
  void group(Index nodes) {
    std::sort(scratch_.begin(), scratch_.end());
    scratch_.erase(std::unique(scratch_.begin(), scratch_.end()), scratch_.end());
    for (std::size_t k = 0; k < scratch_.size();) {
      std::size_t end = k;
      while (end < scratch_.size() && scratch_[end].first == scratch_[k].first) ++end;
      if (end - k >= 2) {
        if (start_.empty()) start_.push_back(0);
        for (std::size_t m = k; m < end; ++m)
          members_.push_back(scratch_[m].second * nodes + scratch_[m].first);
        start_.push_back(members_.size());
      }
      k = end;
    }
  }

  /// g_f,i = sum_p V_p grad S_pi by multi-field node (each particle on its field's nodes).
  template <class Stencils>
  void volume_gradients(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& ps) {
    gradient_.assign(static_cast<std::size_t>(grid.node_count), Vec<D>::Zero());
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const double V = ps.volume(p);
      stencils.for_each_node(grid, p, [&](Index node, double, const auto& dN) { gradient_[node] += V * dN; });
    }
  }

  ThermalContact mode_ = ThermalContact::Insulated;
  double conductance_ = 0.0;
  Index field_nodes_ = 0;  // the contact's nodes per field
  int fields_ = 0;
  std::vector<std::pair<Index, int>> scratch_;  // (grid node, field) in perfect contact
  std::vector<Index> members_;                  // multi-field nodes of each group, by group
  std::vector<std::size_t> start_;              // group g: members_[start_[g] .. start_[g + 1])
  std::vector<Pair> pairs_;                     // conductance: the contacts of this step
  std::vector<Vec<D>> gradient_;                // g_f,i
};

}  // namespace matpoint
