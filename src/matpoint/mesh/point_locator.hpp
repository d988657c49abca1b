// Point location in an element mesh: the host element and local coordinates xi of a point
// (Aulisa & Capodaglio §3.3, particle relocation in the new reference configuration; extraction §7
// "Point location" and A21). Candidates come from a uniform grid of bins over the elements'
// bounding boxes; each candidate is tested by the Newton inverse map (inverse_map.hpp). A point on a
// shared face, edge or corner goes to the lowest element id (candidates are tried in ascending id
// order), and a point on the domain boundary is found thanks to the tolerance on xi. locate() is
// const and uses no scratch space: concurrent calls are safe.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "matpoint/mesh/mesh.hpp"

namespace matpoint::mesh {

template <int D>
struct Location {
  Index element = -1;
  Vec<D> xi;
};

template <int D>
class PointLocator {
 public:
  /// Tolerance on the local coordinates: xi within tolerance outside the reference element still
  /// counts as inside (points on faces, and on the domain boundary up to rounding).
  static constexpr double kDefaultTolerance = 1e-10;

  /// Built for the node coordinates given (the mesh's nodes or a moved configuration of them; the
  /// mesh must outlive the locator). When the configuration moves, call update().
  PointLocator(const Mesh<D>& mesh, std::span<const Vec<D>> node_coordinates,
               double tolerance = kDefaultTolerance);

  /// Rebuilds the bins for new node coordinates of the same mesh.
  void update(std::span<const Vec<D>> node_coordinates);

  /// Elements never to return (per element, 1: excluded), e.g. the elements of FE bodies, which no
  /// particle may enter (Aulisa & Capodaglio §4): a point on a face they share with a background
  /// element goes to the background element. Rebuilds the bins.
  void exclude(std::vector<char> excluded);

  /// Host element and local coordinates; the lowest element id on shared faces; nullopt outside the
  /// mesh. A `hint` element (e.g. the previous host) is tried first and kept when the point lies
  /// inside it by more than the tolerance (then no other element can hold it).
  std::optional<Location<D>> locate(const Vec<D>& x, Index hint = -1) const;

  /// Local coordinates of x in element e (Newton from the centre, then from the nearest node);
  /// nullopt if Newton fails. The result may lie outside the reference element.
  std::optional<Vec<D>> local_coordinates(Index e, const Vec<D>& x) const;

  /// Number of bins per direction (for diagnostics).
  const std::array<int, D>& bins() const { return bins_; }

 private:
  template <class E>
  std::optional<Vec<D>> local_coordinates_as(Index e, const Vec<D>& x) const;
  template <class E>
  std::optional<Location<D>> search_as(const Vec<D>& x, Index hint) const;
  Index bin_of(const Vec<D>& x) const;                          // -1 outside the bins
  std::array<std::pair<int, int>, D> bin_range(Index e) const;  // bins touched by element e's box
  Vec<D> element_boxes();  // fills box_low_/box_high_; returns the mean element extent
  void build_bins();
  void fill_bins();

  const Mesh<D>* mesh_;
  std::vector<Vec<D>> coordinates_;
  double tolerance_;
  std::vector<Vec<D>> box_low_, box_high_;  // per element, enlarged bounding boxes
  Vec<D> origin_, bin_size_;
  std::array<int, D> bins_{};
  std::vector<Index> bin_start_, bin_elements_;  // CSR: elements of bin b in ascending id order
  std::vector<char> excluded_;                   // per element (empty: none)
};

extern template class PointLocator<2>;
extern template class PointLocator<3>;

}  // namespace matpoint::mesh
