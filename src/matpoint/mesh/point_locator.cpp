// Point location by bins and Newton inverse maps (point_locator.hpp).
#include "matpoint/mesh/point_locator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "matpoint/mesh/inverse_map.hpp"

namespace matpoint::mesh {

namespace {

/// Bounding-box enlargement, as a fraction of the node box, for quadratic elements: a quadratic
/// Lagrange interpolant stays within its Lebesgue constant (1.25 per direction, 1.5625 for Q9) times
/// the nodal range, so a curved Q9 or T6 can bulge past its nodes by up to (1.5625 - 1)/2 < 0.3.
constexpr double kQuadraticBulge = 0.3;

}  // namespace

template <int D>
PointLocator<D>::PointLocator(const Mesh<D>& mesh, std::span<const Vec<D>> node_coordinates, double tolerance)
    : mesh_(&mesh), tolerance_(tolerance) {
  if (!(tolerance >= 0.0)) throw std::invalid_argument("PointLocator: tolerance must be >= 0");
  update(node_coordinates);
}

template <int D>
void PointLocator<D>::update(std::span<const Vec<D>> node_coordinates) {
  if (static_cast<Index>(node_coordinates.size()) != mesh_->node_count())
    throw std::invalid_argument("PointLocator: one coordinate per mesh node expected");
  coordinates_.assign(node_coordinates.begin(), node_coordinates.end());
  build_bins();
}

template <int D>
void PointLocator<D>::exclude(std::vector<char> excluded) {
  excluded_ = std::move(excluded);
  build_bins();
}

template <int D>
Vec<D> PointLocator<D>::element_boxes() {
  const Index ne = mesh_->element_count();
  const double bulge = visit_element_type_of_dim<D>(mesh_->shape, [](auto e) {
    using E = decltype(e);  // a B-spline cell lies inside the box of its control points
    return E::kDegree == 2 && E::kShape != ElementShape::BSpline2 ? kQuadraticBulge : 0.0;
  });
  box_low_.assign(ne, Vec<D>::Constant(1e300));
  box_high_.assign(ne, Vec<D>::Constant(-1e300));
  Vec<D> mean = Vec<D>::Zero();
  for (Index e = 0; e < ne; ++e) {
    for (Index n : mesh_->element_nodes(e)) {
      box_low_[e] = box_low_[e].cwiseMin(coordinates_[n]);
      box_high_[e] = box_high_[e].cwiseMax(coordinates_[n]);
    }
    const Vec<D> extent = box_high_[e] - box_low_[e];
    mean += extent / static_cast<double>(ne);
    // Pad: the bulge, plus the physical size of the xi tolerance (about tolerance * extent / 2).
    const Vec<D> pad = (bulge + tolerance_ + 1e-12) * Vec<D>::Constant(extent.maxCoeff());
    box_low_[e] -= pad, box_high_[e] += pad;
  }
  return mean;
}

template <int D>
void PointLocator<D>::build_bins() {
  const Index ne = mesh_->element_count();
  const Vec<D> mean = element_boxes();
  Vec<D> low = Vec<D>::Zero(), high = Vec<D>::Ones();
  if (ne > 0) {
    low = Vec<D>::Constant(1e300), high = Vec<D>::Constant(-1e300);
    for (Index e = 0; e < ne; ++e) low = low.cwiseMin(box_low_[e]), high = high.cwiseMax(box_high_[e]);
  }
  // About one bin per element: bins of the mean element extent, at most 4 ne bins in all.
  double total = 1.0;
  for (int a = 0; a < D; ++a) {
    const double count = ne > 0 ? (high[a] - low[a]) / std::max(mean[a], 1e-300) : 1.0;
    bins_[a] = static_cast<int>(std::clamp(std::round(count), 1.0, 1e6));
    total *= bins_[a];
  }
  for (int a = 0; a < D && total > 4.0 * std::max<Index>(ne, 1); ++a) {
    const double shrink = std::pow(total / (4.0 * std::max<Index>(ne, 1)), 1.0 / D);
    total /= bins_[a];
    bins_[a] = std::max(1, static_cast<int>(bins_[a] / shrink));
    total *= bins_[a];
  }
  origin_ = low;
  for (int a = 0; a < D; ++a) bin_size_[a] = std::max((high[a] - low[a]) / bins_[a], 1e-300);
  fill_bins();
}

template <int D>
std::array<std::pair<int, int>, D> PointLocator<D>::bin_range(Index e) const {
  std::array<std::pair<int, int>, D> range;
  for (int a = 0; a < D; ++a) {
    auto cell = [&](double v) {
      return std::clamp(floor_to_int((v - origin_[a]) / bin_size_[a]), 0, bins_[a] - 1);
    };
    range[a] = {cell(box_low_[e][a]), cell(box_high_[e][a])};
  }
  return range;
}

template <int D>
void PointLocator<D>::fill_bins() {
  Index nbins = 1;
  for (int a = 0; a < D; ++a) nbins *= bins_[a];
  bin_start_.assign(nbins + 1, 0);
  // Two passes (count, then fill) over the bins each element's box touches; elements in id order.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Index> cursor(bin_start_.begin(), bin_start_.end() - 1);
    for (Index e = 0; e < mesh_->element_count(); ++e) {
      if (static_cast<std::size_t>(e) < excluded_.size() && excluded_[static_cast<std::size_t>(e)] != 0)
        continue;
      const auto range = bin_range(e);
      std::array<int, D> i{};
      for (int a = 0; a < D; ++a) i[a] = range[a].first;
      while (true) {
        Index b = 0;
        for (int a = D - 1; a >= 0; --a) b = b * bins_[a] + i[a];
        if (pass == 0)
          ++bin_start_[b + 1];
        else
          bin_elements_[cursor[b]++] = e;
        int a = 0;
        while (a < D && ++i[a] > range[a].second) i[a] = range[a].first, ++a;
        if (a == D) break;
      }
    }
    if (pass == 0) {
      for (Index b = 0; b < nbins; ++b) bin_start_[b + 1] += bin_start_[b];
      bin_elements_.assign(bin_start_.back(), -1);
    }
  }
}

template <int D>
Index PointLocator<D>::bin_of(const Vec<D>& x) const {
  Index b = 0;
  for (int a = D - 1; a >= 0; --a) {
    const double t = (x[a] - origin_[a]) / bin_size_[a];
    if (!(t >= 0.0 && t <= bins_[a])) return -1;
    b = b * bins_[a] + std::min(static_cast<int>(t), bins_[a] - 1);
  }
  return b;
}

template <int D>
template <class E>
std::optional<Vec<D>> PointLocator<D>::local_coordinates_as(Index e, const Vec<D>& x) const {
  const auto nodes = element_coordinates<E>(*mesh_, coordinates_, e);
  auto xi = inverse_map<E>(nodes, x, E::centre(), mesh_->element_variant(e));
  if (xi || E::kDegree == 1) return xi;
  if constexpr (E::kShape == ElementShape::BSpline2) {
    return xi;  // a cell of the uniform B-spline patch is affine: Newton is exact from any start
  } else {
    // Curved elements: retry from the reference position of the nearest node (extraction §7).
    int nearest = 0;
    (nodes.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
    return inverse_map<E>(nodes, x, E::reference_nodes().row(nearest).transpose());
  }
}

template <int D>
template <class E>
std::optional<Location<D>> PointLocator<D>::search_as(const Vec<D>& x, Index hint) const {
  if (hint >= 0 && hint < mesh_->element_count()) {
    const auto xi = local_coordinates_as<E>(hint, x);
    if (xi && E::contains(*xi, -tolerance_)) return Location<D>{hint, *xi};  // strictly inside: unique
  }
  const Index b = bin_of(x);
  if (b < 0) return std::nullopt;
  for (Index k = bin_start_[b]; k < bin_start_[b + 1]; ++k) {
    const Index e = bin_elements_[k];
    if (!((x.array() >= box_low_[e].array()).all() && (x.array() <= box_high_[e].array()).all())) continue;
    const auto xi = local_coordinates_as<E>(e, x);
    if (xi && E::contains(*xi, tolerance_)) return Location<D>{e, *xi};
  }
  return std::nullopt;
}

template <int D>
std::optional<Location<D>> PointLocator<D>::locate(const Vec<D>& x, Index hint) const {
  return visit_element_type_of_dim<D>(mesh_->shape,
                                      [&](auto element) { return search_as<decltype(element)>(x, hint); });
}

template <int D>
std::optional<Vec<D>> PointLocator<D>::local_coordinates(Index e, const Vec<D>& x) const {
  if (e < 0 || e >= mesh_->element_count()) return std::nullopt;
  return visit_element_type_of_dim<D>(
      mesh_->shape, [&](auto element) { return local_coordinates_as<decltype(element)>(e, x); });
}

template class PointLocator<2>;
template class PointLocator<3>;

}  // namespace matpoint::mesh
