// The stored nodes whose values a rank of a decomposed run reports (history sums, condition
// impulses, grid modes, the dynamic FMPM measure, counts): every node is owned by exactly one rank,
// so that a node two ranks store counts once (docs/scale-out.md §2). A serial run owns every node.
#pragma once

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/index_box.hpp"

namespace matpoint {

class OwnedNodes {
 public:
  /// Every node (a serial run).
  OwnedNodes() = default;

  /// The flat node indices [begin, end).
  static OwnedNodes range(Index begin, Index end) {
    OwnedNodes out;
    out.runs_.clear();
    if (begin < end) out.runs_.push_back({begin, end});
    return out;
  }

  /// The nodes of `window` (a rank's stored grid) whose global coordinates lie in `box`: one run of
  /// flat indices per row along x, rows that join merged (a box spanning whole rows is one run).
  template <int D>
  static OwnedNodes box(const Grid<D>& window, const IndexBox<D>& box) {
    const IndexBox<D> owned = box.intersection(window.stored_nodes());
    OwnedNodes out;
    out.runs_.clear();
    if (owned.empty()) return out;
    IndexBox<D> rows = owned;  // the first node of every row
    rows.end[0] = rows.begin[0] + 1;
    const Index length = owned.end[0] - owned.begin[0];
    rows.for_each([&](const std::array<int, D>& c) {
      const Index first = window.node_index(c);
      if (!out.runs_.empty() && out.runs_.back().second == first)
        out.runs_.back().second = first + length;
      else
        out.runs_.push_back({first, first + length});
    });
    return out;
  }

  /// True for every node of a serial run.
  [[nodiscard]] bool all() const { return runs_.size() == 1 && runs_[0] == kEvery; }

  [[nodiscard]] bool contains(Index node) const {
    if (runs_.size() == 1) return node >= runs_[0].first && node < runs_[0].second;
    const auto after =
        std::upper_bound(runs_.begin(), runs_.end(), node,
                         [](Index n, const std::pair<Index, Index>& run) { return n < run.first; });
    return after != runs_.begin() && node < std::prev(after)->second;
  }

  /// Calls fn(begin, end) for each run of owned flat indices below `count` (the stored nodes), in
  /// ascending order.
  template <class Fn>
  void for_each_run(Index count, Fn&& fn) const {
    for (const auto& [begin, end] : runs_)
      if (begin < count) fn(begin, std::min(end, count));
  }

 private:
  static constexpr std::pair<Index, Index> kEvery{0, std::numeric_limits<Index>::max()};
  std::vector<std::pair<Index, Index>> runs_{kEvery};  // ascending, disjoint
};

}  // namespace matpoint
