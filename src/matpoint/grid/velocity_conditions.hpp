// Grid velocity conditions (Nairn 2026 §2.1 task 2.a, lumped form): after the momentum update a
// constrained velocity component of a node is set to its prescribed value. Conditions on domain
// faces include the ghost node layers beyond the face.
#pragma once

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"

#include <vector>

namespace matpoint {

template <int D> class VelocityConditions {
 public:
  VelocityConditions() = default;
  VelocityConditions(const std::vector<VelocityConditionSpec>& specs, const Grid<D>& grid);

  /// Moving walls (Nairn 2026 §3.1): selects the nodes each wall controls at time t (the start of
  /// the step, where the shape functions are evaluated) and their velocities. Call once per step
  /// after the nodal masses are known.
  void select_wall_nodes(double t, const std::vector<double>& mass, double mass_floor);

  /// Sets every constrained component of v at time t (one-sided faces: on the nodes moving into them). Where mass is given, adds to `impulse` the
  /// momentum the constraint injects (m (v_set - v_free)) and to `work` that impulse times the
  /// prescribed velocity: the work done by a moving wall (zero for fixed ones).
  void apply(std::vector<Vec<D>>& v, double t, const std::vector<double>* mass = nullptr,
             Vec<D>* impulse = nullptr, double* work = nullptr) const;

  /// Zeroes every constrained component of v: the condition directions of an FMPM increment
  /// (Nairn 2026 Table 2, bottom block), so that v+(k) keeps the value set on v+(1) (eq. 12).
  /// With `mass`, adds to `impulse` the momentum the zeroing removes, -m_i v_i (a = axis): without
  /// it an increment would conserve momentum, so this is the conditions' share of the increment.
  /// With `work` too, adds that momentum times the prescribed velocity at time t, as apply() does:
  /// the work of a moving wall in the FMPM increments.
  void zero_constrained(std::vector<Vec<D>>& v, const std::vector<double>* mass = nullptr,
                        Vec<D>* impulse = nullptr, double* work = nullptr, double t = 0.0) const {
    auto zero = [&](Index node, int axis, double set) {
      if (mass && impulse) {
        const double dp = -(*mass)[node] * v[node][axis];
        (*impulse)[axis] += dp;
        if (work) *work += dp * set;
      }
      v[node][axis] = 0.0;
    };
    for (const auto& e : entries_) zero(e.node, e.axis, e.function < 0 || !work ? 0.0 : functions_[e.function](t));
    for (const auto& e : wall_entries_) zero(e.node, e.axis, e.value);
  }

  [[nodiscard]] bool has_walls() const { return !walls_.empty(); }
  [[nodiscard]] bool has_one_sided() const { return one_sided_; }

  /// Multi-field (contact) runs: every condition holds on each of `fields` copies of the grid's
  /// N nodes (field f at flat indices f N .. f N + N - 1), walls included.
  void replicate(int fields);

  [[nodiscard]] std::size_t size() const { return entries_.size() + wall_entries_.size(); }

 private:
  struct Entry {
    Index node;
    int axis;
    int function;      // index into functions_, or -1 for zero
    int face_axis = 0;  // one-sided: the face's axis, and
    int approach = 0;   // +1 / -1: holds only while v[face_axis] * approach > 0; 0: always
  };
  /// A one-sided entry holds when its node moves into the face (judged on v before any change).
  [[nodiscard]] static bool holds(const Entry& e, const std::vector<Vec<D>>& v) {
    return e.approach == 0 || v[e.node][e.face_axis] * e.approach > 0.0;
  }
  struct WallEntry {
    Index node;
    int axis;
    double value;
  };
  void select_field_wall_nodes(double t, const std::vector<double>& mass, double mass_floor, Index offset);

  std::vector<Entry> entries_;
  std::vector<TimeFunction> functions_;
  std::vector<VelocityConditionSpec> walls_;
  std::vector<WallEntry> wall_entries_;  // this step's wall nodes
  bool one_sided_ = false;
  Grid<D> grid_;
  int fields_ = 1;
};

}  // namespace matpoint
