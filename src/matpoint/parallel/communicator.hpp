// The ranks of one explicit run and the few ways they talk (issue 23; docs/scale-out.md §4-§7).
// In the serial build, and in a process that MPI did not start, it is one rank and every call is
// the identity or does nothing; only communicator.cpp sees MPI's headers (as core/parallel_session.cpp),
// so the rest of the code compiles with the serial build's flags.
//
// Every collective here gives the same bits on every rank: the sums gather the ranks' values and
// add them in rank order on each rank (MPI_Allreduce may associate differently on different ranks,
// and a sum that steers the run, such as the energy guard's, must not), which costs P values per
// entry: fine for the few dozen numbers a step or an output reduces.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "matpoint/parallel/traffic.hpp"

namespace matpoint {

class Communicator {
 public:
  /// One rank (rank 0 of 1).
  Communicator() = default;
  /// This process' MPI world (MPI_COMM_WORLD), or one rank where MPI is not running.
  [[nodiscard]] static Communicator world();

  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  /// More than one rank: the run is decomposed.
  [[nodiscard]] bool distributed() const { return size_ > 1; }

  // Collectives: every rank calls them, in the same order.
  [[nodiscard]] double max(double value) const;
  [[nodiscard]] double min(double value) const;
  [[nodiscard]] long max(long value) const;
  [[nodiscard]] long min(long value) const;
  [[nodiscard]] long sum(long value) const;
  /// Entry-wise sums over the ranks, added in rank order (identical on every rank).
  void sum(std::vector<double>& values) const;
  /// Entry-wise maxima (exact).
  void max(std::vector<double>& values) const;
  void max(std::vector<int>& values) const;
  /// Every rank's `values`, concatenated in rank order (the ranks may contribute different counts).
  [[nodiscard]] std::vector<double> all_gather(const std::vector<double>& values) const;
  [[nodiscard]] std::vector<long> all_gather(const std::vector<long>& values) const;
  /// Rank `root`'s text, on every rank.
  [[nodiscard]] std::string broadcast(const std::string& text, int root) const;
  void barrier() const;
  /// The collectives above (not `exchange`) that this process ran on more than one rank, and the
  /// wall time in them, waiting for the slowest rank included (summary.json's `parallel`).
  [[nodiscard]] static const Traffic& collectives();

  /// Point to point with sizes both sides know (the halo hand-off): send[k] goes to its rank, and
  /// receive[k] is filled from its rank. Receives are posted before the sends; returns when all
  /// are done.
  struct Message {
    int rank;
    double* data;
    std::size_t count;
  };
  void exchange(const std::vector<Message>& send, const std::vector<Message>& receive) const;
  /// Sizes only the sender knows (particle migration): sends to_rank[r] to rank r (empty: none)
  /// and returns what each rank sent to this one, by rank.
  [[nodiscard]] std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& to_rank) const;

 private:
  Communicator(int rank, int size) : rank_(rank), size_(size) {}
  int rank_ = 0, size_ = 1;
};

}  // namespace matpoint
