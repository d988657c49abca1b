#include "matpoint/grid/velocity_conditions.hpp"

namespace matpoint {

namespace {

template <int D>
bool node_selected(const VelocityConditionSpec& c, const Grid<D>& grid, Index node) {
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
VelocityConditions<D>::VelocityConditions(const std::vector<VelocityConditionSpec>& specs,
                                          const Grid<D>& grid)
    : specs_(specs), grid_(grid) {
  select_nodes();
}

template <int D>
void VelocityConditions<D>::use_window(const Grid<D>& grid) {
  grid_ = grid;
  const int fields = fields_;
  entries_.clear(), functions_.clear(), walls_.clear(), faces_.clear();
  touching_.clear(), held_.clear(), wall_entries_.clear();
  one_sided_ = false;
  fields_ = 1;
  select_nodes();
  if (fields > 1) replicate(fields);
}

template <int D>
void VelocityConditions<D>::select_nodes() {
  const Grid<D>& grid = grid_;
  for (const auto& c : specs_) {
    std::vector<std::pair<int, int>> axis_function;  // (axis, function)
    switch (c.kind) {
      case ConditionKind::MovingWall:
        walls_.push_back(c);
        continue;
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
    const int approach = c.one_sided ? (c.face_side == 0 ? -1 : 1) : 0;
    one_sided_ = one_sided_ || c.one_sided;
    if (c.one_sided) {
      const int a = c.face_axis;
      faces_.push_back({a, c.face_side, c.face_side == 0 ? grid.origin[a] : grid.domain_max()[a]});
    }
    for (Index node = 0; node < grid.node_count; ++node)
      if (node_selected(c, grid, node))
        for (auto [axis, function] : axis_function)
          entries_.push_back({node, axis, function, c.face_axis, approach});
  }
}

template <int D>
void VelocityConditions<D>::replicate(int fields) {
  const std::size_t single = entries_.size() / static_cast<std::size_t>(fields_);
  entries_.resize(single);
  for (int f = 1; f < fields; ++f)
    for (std::size_t k = 0; k < single; ++k) {
      Entry e = entries_[k];
      e.node += f * grid_.node_count;
      entries_.push_back(e);
    }
  fields_ = fields;
}

template <int D>
void VelocityConditions<D>::select_wall_nodes(double t, const std::vector<double>& mass, double mass_floor) {
  wall_entries_.clear();
  for (int f = 0; f < fields_; ++f) select_field_wall_nodes(t, mass, mass_floor, f * grid_.node_count);
}

template <int D>
void VelocityConditions<D>::select_field_wall_nodes(double t, const std::vector<double>& mass,
                                                    double mass_floor, Index offset) {
  for (const auto& w : walls_) {
    const int a = w.normal_axis;
    const double x_wall = w.wall_position + w.wall_velocity.integral(t);
    const double v_wall = w.wall_velocity(t);
    const double tol = 1e-9 * grid_.h[a];
    for (Index node = 0; node < grid_.node_count; ++node) {
      if (!(mass[offset + node] > mass_floor)) continue;
      const double x = grid_.node_position(node)[a];
      const bool controlled = w.material_below ? x >= x_wall - w.depth - tol : x <= x_wall + w.depth + tol;
      if (!controlled) continue;
      // v_i = v_wall + grad v (x_i - x_wall), grad v = v_wall / (x_wall - x_c) for a stretch about x_c
      const double value =
          w.stretch_about ? v_wall * (x - *w.stretch_about) / (x_wall - *w.stretch_about) : v_wall;
      wall_entries_.push_back({offset + node, a, value});
    }
  }
}

template <int D>
void VelocityConditions<D>::apply(std::vector<Vec<D>>& v, double t, const std::vector<double>* mass,
                                  Vec<D>* impulse, double* work) const {
  std::vector<double> value(functions_.size());
  for (std::size_t f = 0; f < functions_.size(); ++f) value[f] = functions_[f](t);
  if (one_sided_ && (held_.empty() || touching_.empty())) {  // decided on the velocities before any change
    held_.clear();
    for (const auto& e : entries_) held_.push_back(static_cast<char>(holds(e, v)));
  }
  // Nairn 2026 Table 2, top block (superposition): first every held condition removes the
  // velocity along its direction (a second condition along the same direction removes 0), then
  // each adds its own prescribed velocity, so conditions on one node add up, v = sum_b v^(b) n^(b).
  const std::size_t count = entries_.size() + wall_entries_.size();
  free_.assign(count, 0.0);
  const auto node_axis = [&](std::size_t k) {
    return k < entries_.size() ? std::pair{entries_[k].node, entries_[k].axis}
                               : std::pair{wall_entries_[k - entries_.size()].node,
                                           wall_entries_[k - entries_.size()].axis};
  };
  const auto held = [&](std::size_t k) { return k >= entries_.size() || !one_sided_ || held_[k] != 0; };
  for (std::size_t k = 0; k < count; ++k) {
    if (!held(k)) continue;
    const auto [node, axis] = node_axis(k);
    free_[k] = v[node][axis];
    v[node][axis] = 0.0;
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (!held(k)) continue;
    const auto [node, axis] = node_axis(k);
    double set = 0.0;
    if (k < entries_.size())
      set = entries_[k].function < 0 ? 0.0 : value[entries_[k].function];
    else
      set = wall_entries_[k - entries_.size()].value;
    v[node][axis] += set;
    if (mass && impulse && work && counts(node)) {  // this condition's share: m (v^(b) - its free component)
      const double dp = (*mass)[node] * (set - free_[k]);
      (*impulse)[axis] += dp;
      *work += dp * set;
    }
  }
}

template class VelocityConditions<1>;
template class VelocityConditions<2>;
template class VelocityConditions<3>;

}  // namespace matpoint
