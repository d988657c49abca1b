// A box of integer coordinates (cells, nodes or bricks): [begin[a], end[a]) along each axis.
// A decomposed run describes with it what a rank owns, stores and shares (docs/scale-out.md §2).
#pragma once

#include <algorithm>
#include <array>

#include "matpoint/core/types.hpp"

namespace matpoint {

template <int D>
struct IndexBox {
  std::array<int, D> begin{}, end{};

  /// True when the box holds no coordinate (end <= begin along some axis).
  [[nodiscard]] bool empty() const {
    for (int a = 0; a < D; ++a)
      if (end[a] <= begin[a]) return true;
    return false;
  }
  [[nodiscard]] bool contains(const std::array<int, D>& c) const {
    for (int a = 0; a < D; ++a)
      if (c[a] < begin[a] || c[a] >= end[a]) return false;
    return true;
  }
  /// The coordinates in both boxes (possibly empty).
  [[nodiscard]] IndexBox intersection(const IndexBox& other) const {
    IndexBox out;
    for (int a = 0; a < D; ++a) {
      out.begin[a] = std::max(begin[a], other.begin[a]);
      out.end[a] = std::min(end[a], other.end[a]);
    }
    return out;
  }
  /// The number of coordinates in the box (0 when empty).
  [[nodiscard]] Index size() const {
    if (empty()) return 0;
    Index n = 1;
    for (int a = 0; a < D; ++a) n *= end[a] - begin[a];
    return n;
  }
  /// Calls fn(c) for every coordinate, the first axis fastest (ascending flat index in any grid
  /// numbered x fastest).
  template <class Fn>
  void for_each(Fn&& fn) const {
    if (empty()) return;
    std::array<int, D> c = begin;
    while (true) {
      fn(c);
      int a = 0;
      while (a < D && ++c[a] == end[a]) c[a] = begin[a], ++a;
      if (a == D) return;
    }
  }
  friend bool operator==(const IndexBox&, const IndexBox&) = default;
};

}  // namespace matpoint
