#include "matpoint/grid/velocity_conditions.hpp"

namespace matpoint {

namespace {

template <int D> bool node_selected(const VelocityConditionSpec& c, const Grid<D>& grid, Index node) {
  const auto ijk = grid.node_coords(node);
  if (c.on_face) {
    const int i = ijk[c.face_axis];
    return c.face_side == 0 ? i <= 0 : i >= grid.cells[c.face_axis];
  }
  const Vec<D> x = grid.node_position(node);
  for (int a = 0; a < D; ++a) {
    const double tol = 1e-9 * grid.h[a];
    if (x[a] < c.box_min[a] - tol || x[a] > c.box_max[a] + tol) return false;
  }
  return true;
}

}  // namespace

template <int D>
VelocityConditions<D>::VelocityConditions(const std::vector<VelocityConditionSpec>& specs, const Grid<D>& grid) {
  for (const auto& c : specs) {
    std::vector<std::pair<int, int>> axis_function;  // (axis, function)
    switch (c.kind) {
      case ConditionKind::Fixed:
        for (int a = 0; a < D; ++a) axis_function.emplace_back(a, -1);
        break;
      case ConditionKind::Slip:
        axis_function.emplace_back(c.normal_axis, -1);
        break;
      case ConditionKind::Velocity:
        for (int a = 0; a < D; ++a)
          if (c.velocity[a]) {
            functions_.push_back(*c.velocity[a]);
            axis_function.emplace_back(a, static_cast<int>(functions_.size()) - 1);
          }
        break;
    }
    for (Index node = 0; node < grid.node_count; ++node)
      if (node_selected(c, grid, node))
        for (auto [axis, function] : axis_function) entries_.push_back({node, axis, function});
  }
}

template <int D>
void VelocityConditions<D>::apply(std::vector<Vec<D>>& v, double t, const std::vector<double>* mass,
                                  Vec<D>* impulse, double* work) const {
  std::vector<double> value(functions_.size());
  for (std::size_t f = 0; f < functions_.size(); ++f) value[f] = functions_[f](t);
  for (const auto& e : entries_) {
    const double set = e.function < 0 ? 0.0 : value[e.function];
    if (mass && impulse && work) {
      const double dp = (*mass)[e.node] * (set - v[e.node][e.axis]);
      (*impulse)[e.axis] += dp;
      *work += dp * set;
    }
    v[e.node][e.axis] = set;
  }
}

template class VelocityConditions<1>;
template class VelocityConditions<2>;
template class VelocityConditions<3>;

}  // namespace matpoint
