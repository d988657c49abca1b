// Thermal boundary conditions on the grid faces (docs/input.md "heat"): a fixed temperature on the
// face's nodes (ghost layers included, as the velocity conditions), or a fixed heat flux into the
// domain through the face, q A_i added to the face's own nodes. A_i = int_face N_i dA is the weak
// form's boundary integral for a uniform q: every basis has N_i = 0 on the face except on the
// face's own nodes (the B-splines' folded edge kernels too, kernels.hpp), and along the face it is
// the product over the other axes of h int N_j, which is h inside and h/2 on the edges for the
// hats but differs within two cells of the edges for the B-splines (quadratic: 0.542 h, 0.958 h).
// Those areas match the nodal capacities, so a uniform flux heats a block uniformly along the
// face, and sum_i A_i is the face's area for every basis. The other faces are insulated (zero flux,
// the natural condition of the weak form). With several velocity fields (contact) every field
// gets the same conditions. The interface of apply/zero_constrained is VelocityConditions' so
// that the FMPM loop (explicit/fmpm.hpp) runs on temperatures unchanged.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/shape/kernels.hpp"

namespace matpoint {

template <int D>
class ThermalConditions {
 public:
  ThermalConditions() = default;
  /// `shape`: the run's basis, whose grid functions give the face areas of the fixed fluxes.
  ThermalConditions(const std::vector<ThermalConditionSpec>& specs, const Grid<D>& grid, int fields,
                    ShapeKind shape = ShapeKind::Linear) {
    for (int b = 0; b < D; ++b) integrals_[b] = grid_function_integrals(shape, grid.cells[b]);
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

  /// A decomposed run: the heat is added only for the grid nodes `owned` (of `field_nodes`, in
  /// every field) this rank owns, so that a node two ranks store counts once when the ranks' heats
  /// are added (the temperatures and flows are set on every node).
  void count_only(OwnedNodes owned, Index field_nodes) {
    counted_ = std::move(owned), field_nodes_ = field_nodes;
  }
  [[nodiscard]] bool counts(Index node) const {
    if (field_nodes_ > 0) node %= field_nodes_;
    return counted_.contains(node);
  }

  /// Sets the fixed temperatures; with `capacity` and `heat`, adds the heat that took,
  /// sum c_i (T_fixed - T_i) over the nodes with capacity.
  void apply(std::vector<double>& T, double /*t*/, const std::vector<double>* capacity = nullptr,
             double* heat = nullptr, double* /*work*/ = nullptr) const {
    for (const auto& e : fixed_) {
      if (heat != nullptr && capacity != nullptr && counts(e.node))
        *heat += (*capacity)[e.node] * (e.value - T[e.node]);
      T[e.node] = e.value;
    }
  }

  /// FMPM loop line (1): the increments of the fixed nodes are zeroed (their heat counted).
  void zero_constrained(std::vector<double>& dT, const std::vector<double>* capacity = nullptr,
                        double* heat = nullptr, double* /*work*/ = nullptr, double /*t*/ = 0.0) const {
    for (const auto& e : fixed_) {
      if (heat != nullptr && capacity != nullptr && counts(e.node)) *heat -= (*capacity)[e.node] * dT[e.node];
      dT[e.node] = 0.0;
    }
  }

  /// Adds the fixed fluxes q A_i to the nodal heat flow (W) of nodes with capacity; returns their
  /// sum (a decomposed run: over the owned nodes).
  double add_flux(std::vector<double>& heat_flow, const std::vector<double>& capacity, double floor) const {
    double total = 0.0;
    for (const auto& e : flux_)
      if (capacity[e.node] > floor) {
        heat_flow[e.node] += e.value;
        if (counts(e.node)) total += e.value;
      }
    return total;
  }

  /// int_0^cells N_j(xi) dxi (xi in cells) of each node j of one axis for the grid functions of
  /// `shape`: the hat's for linear, GIMP and CPDI, the quadratic B-spline's for bspline2, b2gimp
  /// and b2cpdi, the cubic's for bspline3.
  static std::vector<double> grid_function_integrals(ShapeKind shape, int cells) {
    switch (shape) {
      case ShapeKind::BSpline2:
      case ShapeKind::B2GIMP:
      case ShapeKind::B2CPDI:
        return kernel_integrals<QuadraticKernel>(cells);
      case ShapeKind::BSpline3:
        return kernel_integrals<CubicKernel>(cells);
      default:
        return kernel_integrals<HatKernel>(cells);
    }
  }

  /// Three-point Gauss-Legendre on every half cell: exact for the folded kernels, piecewise
  /// polynomials of degree <= 3 with their breaks on nodes or half-nodes.
  template <class Kernel>
  static std::vector<double> kernel_integrals(int cells) {
    if (cells < Kernel::point_width - 1) return kernel_integrals<HatKernel>(cells);  // no room to fold
    std::vector<double> integral(static_cast<std::size_t>(cells) + 1, 0.0);
    const double g = std::sqrt(0.6);
    const std::array<double, 3> at{-g, 0.0, g}, weight{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int half = 0; half < 2 * cells; ++half)
      for (int q = 0; q < 3; ++q) {
        double w[kMaxKernelWidth], dw[kMaxKernelWidth];
        const int i0 = point_on_grid<Kernel>(0.5 * half + 0.25 * (1.0 + at[q]), cells, w, dw);
        for (int k = 0; k < Kernel::point_width; ++k) integral[i0 + k] += 0.25 * weight[q] * w[k];
      }
    return integral;
  }

 private:
  struct Entry {
    Index node;
    double value;  // temperature, or q A_i
  };

  /// A_i = prod over the other axes b of h_b int N_j(x_b) dx_b.
  double face_area(const Grid<D>& grid, const std::array<int, D>& ijk, int axis) const {
    double area = 1.0;
    for (int b = 0; b < D; ++b) {
      if (b == axis) continue;
      if (ijk[b] < 0 || ijk[b] > grid.cells[b]) return 0.0;  // ghost nodes carry no face
      area *= grid.h[b] * integrals_[b][ijk[b]];
    }
    return area;
  }

  std::array<std::vector<double>, D> integrals_;  // per axis: int N_j dxi by node j
  std::vector<Entry> fixed_, flux_;
  OwnedNodes counted_;  // every node unless count_only
  Index field_nodes_ = 0;
};

}  // namespace matpoint
