#include "matpoint/parallel/communicator.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <stdexcept>

#ifdef MATPOINT_HAS_PETSC
#define OMPI_SKIP_MPICXX 1  // the C interface only (OpenMPI's C++ bindings warn under -Wextra)
#include <mpi.h>
#endif

namespace matpoint {

#ifdef MATPOINT_HAS_PETSC

namespace {

Traffic collective_traffic;

/// Times one collective into collective_traffic.
class Timed {
 public:
  Timed() : t0_(Traffic::start()) {}
  ~Timed() {
    collective_traffic.waited(t0_);  // a collective is all waiting
    collective_traffic.done(t0_);
  }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  Traffic::Clock t0_;
};

int checked(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI failed in ") + what);
  return code;
}

template <class T>
std::vector<T> gather_all(const std::vector<T>& values, MPI_Datatype type, int size) {
  const int mine = static_cast<int>(values.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size) + 1, 0);
  checked(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<T> all(static_cast<std::size_t>(offsets[size]));
  checked(MPI_Allgatherv(values.data(), mine, type, all.data(), counts.data(), offsets.data(), type,
                         MPI_COMM_WORLD),
          "MPI_Allgatherv");
  return all;
}

/// Entry-wise combination over the ranks, in rank order, identical on every rank.
template <class T, class Combine>
void combine_in_rank_order(std::vector<T>& values, MPI_Datatype type, int size, Combine combine) {
  if (size == 1) return;
  const Timed timed;
  const std::size_t n = values.size();
  const std::vector<T> all = gather_all(values, type, size);
  if (all.size() != n * static_cast<std::size_t>(size))
    throw std::logic_error("Communicator: the ranks reduced vectors of different lengths");
  for (std::size_t i = 0; i < n; ++i) {
    T v = all[i];
    for (int r = 1; r < size; ++r) v = combine(v, all[static_cast<std::size_t>(r) * n + i]);
    values[i] = v;
  }
}

}  // namespace

Communicator Communicator::world() {
  int running = 0;
  MPI_Initialized(&running);
  if (running == 0) return {};
  int finished = 0;
  MPI_Finalized(&finished);
  if (finished != 0) return {};
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return {rank, size};
}

double Communicator::max(double value) const {
  std::vector<double> v{value};
  max(v);
  return v[0];
}
double Communicator::min(double value) const {
  std::vector<double> v{-value};
  max(v);
  return -v[0];
}
long Communicator::max(long value) const {
  if (size_ == 1) return value;
  const Timed timed;
  long out = value;
  checked(MPI_Allreduce(&value, &out, 1, MPI_LONG, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}
long Communicator::min(long value) const {
  if (size_ == 1) return value;
  const Timed timed;
  long out = value;
  checked(MPI_Allreduce(&value, &out, 1, MPI_LONG, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}
long Communicator::sum(long value) const {
  if (size_ == 1) return value;
  const Timed timed;
  long out = value;
  checked(MPI_Allreduce(&value, &out, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}
void Communicator::sum(std::vector<double>& values) const {
  combine_in_rank_order(values, MPI_DOUBLE, size_, std::plus<>());
}
void Communicator::max(std::vector<double>& values) const {
  // NaN wins, so that a failure seen on one rank is seen on all.
  combine_in_rank_order(values, MPI_DOUBLE, size_, [](double a, double b) {
    if (a != a) return a;  // NOLINT(misc-redundant-expression): a NaN test
    if (b != b) return b;  // NOLINT(misc-redundant-expression)
    return b > a ? b : a;
  });
}
void Communicator::max(std::vector<int>& values) const {
  if (size_ == 1 || values.empty()) return;
  const Timed timed;
  checked(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_INT, MPI_MAX,
                        MPI_COMM_WORLD),
          "MPI_Allreduce");
}
std::vector<double> Communicator::all_gather(const std::vector<double>& values) const {
  if (size_ == 1) return values;
  const Timed timed;
  return gather_all(values, MPI_DOUBLE, size_);
}
std::vector<long> Communicator::all_gather(const std::vector<long>& values) const {
  if (size_ == 1) return values;
  const Timed timed;
  return gather_all(values, MPI_LONG, size_);
}
std::string Communicator::broadcast(const std::string& text, int root) const {
  if (size_ == 1) return text;
  const Timed timed;
  long length = static_cast<long>(text.size());
  checked(MPI_Bcast(&length, 1, MPI_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = rank_ == root ? text : std::string(static_cast<std::size_t>(length), '\0');
  checked(MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
}
void Communicator::barrier() const {
  if (size_ == 1) return;
  const Timed timed;
  checked(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}
const Traffic& Communicator::collectives() { return collective_traffic; }

void Communicator::exchange(const std::vector<Message>& send, const std::vector<Message>& receive) const {
  if (size_ == 1) return;
  constexpr int kTag = 23;
  std::vector<MPI_Request> requests;
  requests.reserve(send.size() + receive.size());
  for (const auto& m : receive) {
    requests.emplace_back();
    checked(MPI_Irecv(m.data, static_cast<int>(m.count), MPI_DOUBLE, m.rank, kTag, MPI_COMM_WORLD,
                      &requests.back()),
            "MPI_Irecv");
  }
  for (const auto& m : send) {
    requests.emplace_back();
    checked(MPI_Isend(m.data, static_cast<int>(m.count), MPI_DOUBLE, m.rank, kTag, MPI_COMM_WORLD,
                      &requests.back()),
            "MPI_Isend");
  }
  checked(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
          "MPI_Waitall");
}

std::vector<std::vector<char>> Communicator::exchange(const std::vector<std::vector<char>>& to_rank) const {
  if (size_ == 1) return to_rank;
  const auto P = static_cast<std::size_t>(size_);
  std::vector<long> send_counts(P), receive_counts(P);
  for (std::size_t r = 0; r < P; ++r) send_counts[r] = static_cast<long>(to_rank[r].size());
  checked(MPI_Alltoall(send_counts.data(), 1, MPI_LONG, receive_counts.data(), 1, MPI_LONG, MPI_COMM_WORLD),
          "MPI_Alltoall");
  std::vector<std::vector<char>> received(P);
  std::vector<MPI_Request> requests;
  constexpr int kTag = 24;
  for (std::size_t r = 0; r < P; ++r) {
    if (receive_counts[r] == 0 || static_cast<int>(r) == rank_) continue;
    if (receive_counts[r] > std::numeric_limits<int>::max())
      throw std::runtime_error("Communicator::exchange: a message over 2 GiB");
    received[r].resize(static_cast<std::size_t>(receive_counts[r]));
    requests.emplace_back();
    checked(MPI_Irecv(received[r].data(), static_cast<int>(receive_counts[r]), MPI_BYTE, static_cast<int>(r),
                      kTag, MPI_COMM_WORLD, &requests.back()),
            "MPI_Irecv");
  }
  for (std::size_t r = 0; r < P; ++r) {
    if (send_counts[r] == 0 || static_cast<int>(r) == rank_) continue;
    requests.emplace_back();
    checked(MPI_Isend(to_rank[r].data(), static_cast<int>(send_counts[r]), MPI_BYTE, static_cast<int>(r),
                      kTag, MPI_COMM_WORLD, &requests.back()),
            "MPI_Isend");
  }
  checked(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
          "MPI_Waitall");
  received[static_cast<std::size_t>(rank_)] = to_rank[static_cast<std::size_t>(rank_)];
  return received;
}

#else  // the serial build: one rank

Communicator Communicator::world() { return {}; }
double Communicator::max(double value) const { return value; }
double Communicator::min(double value) const { return value; }
long Communicator::max(long value) const { return value; }
long Communicator::min(long value) const { return value; }
long Communicator::sum(long value) const { return value; }
void Communicator::sum(std::vector<double>&) const {}
void Communicator::max(std::vector<double>&) const {}
void Communicator::max(std::vector<int>&) const {}
std::vector<double> Communicator::all_gather(const std::vector<double>& values) const { return values; }
std::vector<long> Communicator::all_gather(const std::vector<long>& values) const { return values; }
std::string Communicator::broadcast(const std::string& text, int) const { return text; }
void Communicator::barrier() const {}
const Traffic& Communicator::collectives() {
  static const Traffic none;
  return none;
}
void Communicator::exchange(const std::vector<Message>&, const std::vector<Message>&) const {}
std::vector<std::vector<char>> Communicator::exchange(const std::vector<std::vector<char>>& to_rank) const {
  return to_rank;
}

#endif

}  // namespace matpoint
