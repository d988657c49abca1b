// Grid velocity conditions (Nairn 2026 §2.1 task 2.a, lumped form): after the momentum update a
// constrained velocity component of a node is set to its prescribed value. Conditions on domain
// faces include the ghost node layers beyond the face.
#pragma once

#include <limits>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

template <int D>
class VelocityConditions {
 public:
  VelocityConditions() = default;
  VelocityConditions(const std::vector<VelocityConditionSpec>& specs, const Grid<D>& grid);

  /// Moving walls (Nairn 2026 §3.1): selects the nodes each wall controls at time t (the start of
  /// the step, where the shape functions are evaluated) and their velocities. Call once per step
  /// after the nodal masses are known.
  void select_wall_nodes(double t, const std::vector<double>& mass, double mass_floor);

  /// Sets every constrained component of v at time t (one-sided faces: on the nodes moving into them);
  /// conditions on one node along one direction add up (Nairn 2026 Table 2). Where
  /// mass is given, adds to `impulse` the momentum the constraint injects (m (v_set - v_free)) and to `work`
  /// that impulse times the prescribed velocity: the work done by a moving wall (zero for fixed ones).
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
      if (mass && impulse && counts(node)) {
        const double dp = -(*mass)[node] * v[node][axis];
        (*impulse)[axis] += dp;
        if (work) *work += dp * set;
      }
      v[node][axis] = 0.0;
    };
    for (const auto& e : entries_)
      zero(e.node, e.axis, e.function < 0 || !work ? 0.0 : functions_[e.function](t));
    for (const auto& e : wall_entries_) zero(e.node, e.axis, e.value);
  }

  /// A decomposed run: impulse and work are added only for the nodes this rank owns, so that a
  /// node two ranks store counts once when the ranks' sums are added (the velocities are set on
  /// every node). `owned` names grid nodes (of N): a multi-field run counts every field's copy.
  void count_only(OwnedNodes owned) { counted_ = std::move(owned); }
  [[nodiscard]] bool counts(Index node) const {
    if (fields_ > 1) node %= grid_.node_count;
    return counted_.contains(node);
  }

  [[nodiscard]] bool has_walls() const { return !walls_.empty(); }
  [[nodiscard]] bool has_one_sided() const { return one_sided_; }

  /// A one-sided face: its axis, side (0: the low face, 1: the high one) and position.
  struct Face {
    int axis;
    int side;
    double position;
  };
  [[nodiscard]] const std::vector<Face>& one_sided_faces() const { return faces_; }
  /// One-sided faces are rigid-wall contacts: a node is held only while the body touches the face
  /// there (flags per node over every field, set each step by mark_nodes_touching_faces) and the
  /// node moves into the face. Without flags (never set) every node of the face counts as
  /// touching. The first apply() after touching() decides which nodes are held, from the velocities
  /// it is given; the later applies of the step (USF, MUSL) hold the same nodes, so that the
  /// velocities that move the particles and those that strain them see the same contact.
  [[nodiscard]] std::vector<char>& touching() {
    held_.clear();
    return touching_;
  }

  /// Multi-field (contact) runs: every condition holds on each of `fields` copies of the grid's
  /// N nodes (field f at flat indices f N .. f N + N - 1), walls included.
  void replicate(int fields);

  /// A decomposed run's rank stores another window of the grid (Grid::window): the conditions'
  /// nodes are selected anew among the stored ones (in every field). The counted range
  /// (count_only) is the caller's to set again.
  void use_window(const Grid<D>& grid);

  [[nodiscard]] std::size_t size() const { return entries_.size() + wall_entries_.size(); }

 private:
  OwnedNodes counted_;  // every node unless count_only
  struct Entry {
    Index node;
    int axis;
    int function;       // index into functions_, or -1 for zero
    int face_axis = 0;  // one-sided: the face's axis, and
    int approach = 0;   // +1 / -1: holds only while v[face_axis] * approach > 0; 0: always
  };
  /// A one-sided entry holds when the body touches the face at its node and the node moves into
  /// the face (judged on v before any change).
  [[nodiscard]] bool holds(const Entry& e, const std::vector<Vec<D>>& v) const {
    if (e.approach == 0) return true;
    const bool touches = touching_.empty() || touching_[e.node] != 0;
    return touches && v[e.node][e.face_axis] * e.approach > 0.0;
  }
  struct WallEntry {
    Index node;
    int axis;
    double value;
  };
  void select_field_wall_nodes(double t, const std::vector<double>& mass, double mass_floor, Index offset);
  /// The nodes of grid_ (one field) each condition of specs_ holds.
  void select_nodes();

  std::vector<Entry> entries_;
  std::vector<TimeFunction> functions_;
  std::vector<VelocityConditionSpec> walls_;
  std::vector<WallEntry> wall_entries_;  // this step's wall nodes
  bool one_sided_ = false;
  std::vector<Face> faces_;           // the one-sided faces
  std::vector<char> touching_;        // per node (every field): a body touches a one-sided face there
  mutable std::vector<char> held_;    // per entry: this step's one-sided decision (apply() caches it)
  mutable std::vector<double> free_;  // apply()'s scratch: each condition's component before it
  std::vector<VelocityConditionSpec> specs_;
  Grid<D> grid_;
  int fields_ = 1;
};

}  // namespace matpoint
