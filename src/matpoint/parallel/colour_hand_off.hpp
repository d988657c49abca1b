// The particle-to-grid sums of a decomposed explicit run, equal to the serial run's bit for bit
// (issue 23; docs/scale-out.md §6, "What stage 1 built").
//
// The serial scatter visits the bricks colour by colour (grid/brick_schedule.hpp): a node's value
// is the running sum over the colours, and within a colour exactly one brick adds to it. Each rank
// scatters the bricks it owns in the same colour order into its own copy of the grid. After colour
// c, the brick of colour c that covers a node (at most one) has the node's current value on its
// owner's copy; when another rank stores that node too, the owner sends it, and the other rank
// overwrites its copy. Before every colour, therefore, every rank that stores a node holds the same
// value, and after the last one the complete serial sum, added in the serial order. The lists of
// which nodes go where depend only on the partition and the stencils' reach, so both sides build
// them alike and the messages carry values only. The lists name grid nodes (of N); an array of a
// multi-field (contact) run holds every field's copy of them (NodeArray::nodes = fields x N), and
// each listed node carries its value in every field, field f at f N + node.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/parallel/box_partition.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/parallel/traffic.hpp"

namespace matpoint {

template <int D>
class ColourHandOff final : public BrickBoundary {
 public:
  ColourHandOff(const Grid<D>& grid, const BoxPartition<D>& partition, const Communicator& comm)
      : grid_(grid), partition_(partition), comm_(comm) {}

  /// The largest reach of any rank, never less than an earlier step's (so that the lists are
  /// rebuilt only when a stencil grows); rebuilds the lists when it changed.
  void agree_reach(int& below, int& above) override {
    std::vector<int> reach{below, above, below_, above_};
    comm_.max(reach);
    below = std::max(reach[0], reach[2]);
    above = std::max(reach[1], reach[3]);
    if (below != below_ || above != above_ || peers_.empty()) build(below, above);
  }

  /// The partition or this rank's grid window changed: the lists are rebuilt at the next
  /// agree_reach (they are flat indices of the window).
  void partition_changed() { peers_.clear(); }

  /// The reach every rank agreed on at the last agree_reach ({-1, -1} before the first).
  [[nodiscard]] std::pair<int, int> reach() const { return {below_, above_}; }

  void after_colour(int colour, const NodeArray* arrays, int count) const override {
    const auto& peers = peers_[static_cast<std::size_t>(colour)];
    if (peers.empty()) return;
    const auto t0 = Traffic::start();
    // The doubles per listed node: every array's width times its fields (a multi-field array
    // holds the N nodes of the lists once per field, field f at f N + node).
    const Index n = grid_.node_count;
    int width = 0;
    for (int k = 0; k < count; ++k) width += arrays[k].width * static_cast<int>(arrays[k].nodes / n);
    std::vector<Communicator::Message> send, receive;
    buffers_.resize(2 * peers.size());
    for (std::size_t j = 0; j < peers.size(); ++j) {
      const Peer& peer = peers[j];
      auto& out = buffers_[2 * j];
      auto& in = buffers_[2 * j + 1];
      out.resize(peer.send.size() * static_cast<std::size_t>(width));
      in.resize(peer.receive.size() * static_cast<std::size_t>(width));
      double* o = out.data();
      for (const Index node : peer.send)
        for (int k = 0; k < count; ++k)
          for (Index f = node; f < arrays[k].nodes; f += n)
            for (int w = 0; w < arrays[k].width; ++w) *o++ = arrays[k].data[f * arrays[k].width + w];
      if (!out.empty()) send.push_back({peer.rank, out.data(), out.size()});
      traffic.sent(out.size() * sizeof(double));
      if (!in.empty()) receive.push_back({peer.rank, in.data(), in.size()});
    }
    const auto t1 = Traffic::start();
    comm_.exchange(send, receive);
    traffic.waited(t1);
    for (std::size_t j = 0; j < peers.size(); ++j) {
      const double* i = buffers_[2 * j + 1].data();
      for (const Index node : peers[j].receive)
        for (int k = 0; k < count; ++k)
          for (Index f = node; f < arrays[k].nodes; f += n)
            for (int w = 0; w < arrays[k].width; ++w) arrays[k].data[f * arrays[k].width + w] = *i++;
    }
    traffic.done(t0);
  }

  /// Messages, bytes and seconds of every hand-off so far (summary.json's `parallel`).
  mutable Traffic traffic;

  /// Nodes this rank sends to / receives from other ranks after each colour (for the tests).
  [[nodiscard]] std::size_t send_count(int colour) const {
    std::size_t n = 0;
    for (const auto& peer : peers_[static_cast<std::size_t>(colour)]) n += peer.send.size();
    return n;
  }

 private:
  struct Peer {
    int rank;
    std::vector<Index> send, receive;  // flat node indices, ascending
  };

  /// Along axis a, the brick whose nodes [k B - below, end_k - 1 + above] hold node coordinate n
  /// and whose coordinate is c_a modulo m; -1 for none (the colouring makes it unique).
  [[nodiscard]] int covering_brick(int a, int n, int c_a, int m) const {
    constexpr auto B = [](int axis) { return BrickSchedule<D>::brick_cells(axis); };
    const int bricks = BrickSchedule<D>::bricks_along(grid_, a);
    const int first = std::max(0, (n - above_) / B(a) - 1), last = std::min(bricks - 1, (n + below_) / B(a));
    for (int k = first; k <= last; ++k) {
      const int end = std::min((k + 1) * B(a), grid_.cells[a]);
      if (k % m == c_a && n >= k * B(a) - below_ && n <= end - 1 + above_) return k;
    }
    return -1;
  }

  void build(int below, int above) {
    below_ = below, above_ = above;
    const int m = BrickSchedule<D>::colours_per_axis_for(below, above);
    int colours = 1;
    for (int a = 0; a < D; ++a) colours *= m;
    peers_.assign(static_cast<std::size_t>(colours), {});
    const int me = comm_.rank(), ghost = grid_.ghost;
    for (int colour = 0; colour < colours; ++colour) {
      std::array<int, D> c{};
      for (int a = 0, rest = colour; a < D; ++a, rest /= m) c[a] = rest % m;
      // Per axis, the covering brick of every node coordinate n (at n + ghost), or -1.
      std::array<std::vector<int>, D> cover;
      for (int a = 0; a < D; ++a) {
        cover[a].resize(static_cast<std::size_t>(grid_.cells[a] + 1 + 2 * ghost));
        for (int n = -ghost; n <= grid_.cells[a] + ghost; ++n)
          cover[a][static_cast<std::size_t>(n + ghost)] = covering_brick(a, n, c[a], m);
      }
      for (int r = 0; r < comm_.size(); ++r) {
        if (r == me) continue;
        Peer peer{r, {}, {}};
        // Both ranks walk the nodes they share in the same (ascending) order, so the lists match.
        partition_.shared_nodes_of(me, r, below, above).for_each([&](const std::array<int, D>& node) {
          std::array<int, D> brick{};
          for (int a = 0; a < D; ++a) {
            brick[a] = cover[a][static_cast<std::size_t>(node[a] + ghost)];
            if (brick[a] < 0) return;  // no brick of this colour reaches the node
          }
          const int owner = partition_.owner_of_brick(partition_.brick_index(brick));
          if (owner == me)
            peer.send.push_back(grid_.node_index(node));
          else if (owner == r)
            peer.receive.push_back(grid_.node_index(node));
        });
        if (!peer.send.empty() || !peer.receive.empty())
          peers_[static_cast<std::size_t>(colour)].push_back(std::move(peer));
      }
    }
  }

  const Grid<D>& grid_;
  const BoxPartition<D>& partition_;
  Communicator comm_;
  int below_ = -1, above_ = -1;
  std::vector<std::vector<Peer>> peers_;  // by colour
  mutable std::vector<std::vector<double>> buffers_;
};

}  // namespace matpoint
