// Thermal boundary conditions on the grid faces (docs/input.md "heat"): a fixed temperature on the
// face's nodes (ghost layers included, as the velocity conditions), or a fixed heat flux into the
// domain through the face, q A_i added to the face's own nodes (A_i: the face area a node stands
// for, h per other axis, halved on the face's edges). The other faces are insulated (zero flux,
// the natural condition of the weak form). With several velocity fields (contact) every field
// gets the same conditions. The interface of apply/zero_constrained is VelocityConditions' so
// that the FMPM loop (explicit/fmpm.hpp) runs on temperatures unchanged.
#pragma once

#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

template <int D>
class ThermalConditions {
 public:
  ThermalConditions() = default;
  ThermalConditions(const std::vector<ThermalConditionSpec>& specs, const Grid<D>& grid, int fields) {
    for (Index f = 0; f < fields; ++f)
      for (Index n = 0; n < grid.node_count; ++n) {
        const auto ijk = grid.node_coords(n);
        for (const auto& c : specs) {
          const int i = ijk[c.face_axis];
          const bool on_face = c.face_side == 0 ? i <= 0 : i >= grid.cells[c.face_axis];
          const Index node = f * grid.node_count + n;
          if (c.kind == ThermalConditionKind::Temperature && on_face) fixed_.push_back({node, c.value});
          const bool face_node = i == (c.face_side == 0 ? 0 : grid.cells[c.face_axis]);
          if (c.kind == ThermalConditionKind::Flux && face_node)
            flux_.push_back({node, c.value * face_area(grid, ijk, c.face_axis)});
        }
      }
  }

  [[nodiscard]] bool empty() const { return fixed_.empty() && flux_.empty(); }

  /// Sets the fixed temperatures; with `capacity` and `heat`, adds the heat that took,
  /// sum c_i (T_fixed - T_i) over the nodes with capacity.
  void apply(std::vector<double>& T, double /*t*/, const std::vector<double>* capacity = nullptr,
             double* heat = nullptr, double* /*work*/ = nullptr) const {
    for (const auto& e : fixed_) {
      if (heat != nullptr && capacity != nullptr) *heat += (*capacity)[e.node] * (e.value - T[e.node]);
      T[e.node] = e.value;
    }
  }

  /// FMPM loop line (1): the increments of the fixed nodes are zeroed (their heat counted).
  void zero_constrained(std::vector<double>& dT, const std::vector<double>* capacity = nullptr,
                        double* heat = nullptr, double* /*work*/ = nullptr, double /*t*/ = 0.0) const {
    for (const auto& e : fixed_) {
      if (heat != nullptr && capacity != nullptr) *heat -= (*capacity)[e.node] * dT[e.node];
      dT[e.node] = 0.0;
    }
  }

  /// Adds the fixed fluxes q A_i to the nodal heat flow (W) of nodes with capacity; returns their sum.
  double add_flux(std::vector<double>& heat_flow, const std::vector<double>& capacity, double floor) const {
    double total = 0.0;
    for (const auto& e : flux_)
      if (capacity[e.node] > floor) {
        heat_flow[e.node] += e.value;
        total += e.value;
      }
    return total;
  }

 private:
  struct Entry {
    Index node;
    double value;  // temperature, or q A_i
  };

  static double face_area(const Grid<D>& grid, const std::array<int, D>& ijk, int axis) {
    double area = 1.0;
    for (int b = 0; b < D; ++b) {
      if (b == axis) continue;
      if (ijk[b] < 0 || ijk[b] > grid.cells[b]) return 0.0;  // ghost nodes carry no face
      area *= (ijk[b] == 0 || ijk[b] == grid.cells[b]) ? 0.5 * grid.h[b] : grid.h[b];
    }
    return area;
  }

  std::vector<Entry> fixed_, flux_;
};

}  // namespace matpoint
