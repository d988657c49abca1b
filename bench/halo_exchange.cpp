// The halo exchange of the explicit solver's particle-to-grid transfer on P ranks (issue 23,
// docs/scale-out.md "The measurement"): on an N x N grid of nodes with 3 doubles per node (mass and
// two momentum components), every rank has scattered into its owned nodes and a ghost layer of
// width g around them; the ghost contributions are ADDED to the owners, then the owners' sums are
// copied back to the ghosts. Three ways, on the same partition (PETSc's choice for the DMDA):
//   dmda   PETSc DMDA (DMDACreate2d, box stencil of width g): VecZeroEntries(global),
//          DMLocalToGlobal(ADD_VALUES), DMGlobalToLocal(INSERT_VALUES)
//   mpi    plain MPI on our own ghosted arrays: MPI_Irecv / MPI_Isend of packed boundary strips,
//          received sums added in ascending neighbour rank order, then the owners' strips sent back
//   sf     PETSc PetscSF on the same arrays as `mpi` (ghost nodes as leaves, their owners' nodes as
//          roots): PetscSFReduce(MPI_SUM), then PetscSFBcast(MPI_REPLACE)
// Before each exchange every rank fills its whole ghosted array with (1, 2, 3) per node; the check
// (first repetition of every method) is that afterwards each node of the ghosted array holds
// (1, 2, 3) times the number of ranks whose ghosted box contains the node, counted here from the
// boxes themselves. Each exchange is timed alone (barrier, MPI_Wtime, exchange, MPI_Wtime), the
// slowest rank's time counts, and the median over the repetitions is printed.
//
// Build (not through CMake; needs libpetsc-real-dev and OpenMPI):
//   mpicxx -O2 -std=c++20 bench/halo_exchange.cpp -o /tmp/halo_exchange $(pkg-config --cflags --libs PETSc)
// Run (as root OpenMPI needs the two OMPI_ALLOW_* variables; more ranks than cores: --oversubscribe):
//   OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -n 2 --oversubscribe /tmp/halo_exchange
// Arguments (optional): sizes as N[:repetitions] ..., e.g. `256:2000 1024:400 2048:150` (the default);
// HALO_METHODS=mpi (or dmda, sf, a comma list) runs only those methods; HALO_PERCENTILES=1 also
// prints p10 / p25 / p50 / p75 / p90 / max of each method.

#include <petscdmda.h>
#include <petscsf.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr int kDof = 3;  // mass + 2 momentum components

/// A half-open box of nodes [x0, x1) x [y0, y1).
struct Box {
  PetscInt x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  [[nodiscard]] bool empty() const { return x1 <= x0 || y1 <= y0; }
  [[nodiscard]] bool contains(PetscInt i, PetscInt j) const { return i >= x0 && i < x1 && j >= y0 && j < y1; }
  [[nodiscard]] PetscInt width() const { return x1 - x0; }
  [[nodiscard]] PetscInt nodes() const { return empty() ? 0 : (x1 - x0) * (y1 - y0); }
};

Box intersect(const Box& a, const Box& b) {
  return {std::max(a.x0, b.x0), std::min(a.x1, b.x1), std::max(a.y0, b.y0), std::min(a.y1, b.y1)};
}

/// The partition of the DMDA: rank r = a + m b owns columns [xcut[a], xcut[a+1]) and rows
/// [ycut[b], ycut[b+1]) (PETSc numbers a DMDA's ranks x fastest); its ghosted box is the owned box
/// grown by g on every side and clipped to the grid (DM_BOUNDARY_NONE, box stencil).
struct Partition {
  PetscInt N = 0, g = 0, m = 1, n = 1;
  std::vector<PetscInt> xcut, ycut;
  [[nodiscard]] int ranks() const { return static_cast<int>(m * n); }
  [[nodiscard]] Box owned(int r) const {
    const PetscInt a = r % m, b = r / m;
    return {xcut[a], xcut[a + 1], ycut[b], ycut[b + 1]};
  }
  [[nodiscard]] Box ghosted(int r) const {
    const Box o = owned(r);
    return {std::max<PetscInt>(0, o.x0 - g), std::min(N, o.x1 + g), std::max<PetscInt>(0, o.y0 - g),
            std::min(N, o.y1 + g)};
  }
  /// The rank that owns node (i, j).
  [[nodiscard]] int owner(PetscInt i, PetscInt j) const {
    const auto a = std::upper_bound(xcut.begin(), xcut.end(), i) - xcut.begin() - 1;
    const auto b = std::upper_bound(ycut.begin(), ycut.end(), j) - ycut.begin() - 1;
    return static_cast<int>(a + m * b);
  }
};

/// Offset of node (i, j) in a ghosted array over `box` (x fastest, kDof values per node: the layout
/// of a DMDA local vector).
PetscInt offset(const Box& box, PetscInt i, PetscInt j) { return ((j - box.y0) * box.width() + (i - box.x0)) * kDof; }

void fill(double* a, PetscInt nodes) {
  for (PetscInt k = 0; k < nodes; ++k)
    for (int c = 0; c < kDof; ++c) a[k * kDof + c] = c + 1.0;
}

/// Nodes of the ghosted array of `me` whose values are wrong after an exchange: value (c + 1) times
/// the number of ranks whose ghosted box holds the node.
long check(const Partition& part, int me, const double* a) {
  const Box mine = part.ghosted(me);
  long wrong = 0;
  for (PetscInt j = mine.y0; j < mine.y1; ++j)
    for (PetscInt i = mine.x0; i < mine.x1; ++i) {
      int touching = 0;
      for (int r = 0; r < part.ranks(); ++r) touching += part.ghosted(r).contains(i, j) ? 1 : 0;
      for (int c = 0; c < kDof; ++c)
        if (a[offset(mine, i, j) + c] != (c + 1.0) * touching) {
          ++wrong;
          break;
        }
    }
  return wrong;
}

/// The plain MPI exchange: per neighbour, the strip of my ghost nodes it owns and the strip of my
/// owned nodes in its ghost layer.
class PlainExchange {
 public:
  PlainExchange(const Partition& part, int me) : box_(part.ghosted(me)) {
    const Box owned = part.owned(me);
    for (int q = 0; q < part.ranks(); ++q) {  // every rank: this benchmark runs on a few
      if (q == me) continue;
      const Box theirs = intersect(box_, part.owned(q));     // my ghosts that q owns
      const Box mine = intersect(owned, part.ghosted(q));    // my owned nodes that q holds as ghosts
      if (theirs.empty() && mine.empty()) continue;
      neighbours_.push_back({q, theirs, mine, std::vector<double>(theirs.nodes() * kDof),
                             std::vector<double>(mine.nodes() * kDof)});
    }
    requests_.resize(2 * neighbours_.size());
  }

  void exchange(double* a) {
    // 1. ghost contributions to their owners, added in ascending neighbour rank order
    const auto n = neighbours_.size();
    for (std::size_t k = 0; k < n; ++k) {
      auto& nb = neighbours_[k];
      MPI_Irecv(nb.mine_buffer.data(), static_cast<int>(nb.mine_buffer.size()), MPI_DOUBLE, nb.rank, 1,
                PETSC_COMM_WORLD, &requests_[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      auto& nb = neighbours_[k];
      pack(a, nb.theirs, nb.theirs_buffer.data());
      MPI_Isend(nb.theirs_buffer.data(), static_cast<int>(nb.theirs_buffer.size()), MPI_DOUBLE, nb.rank, 1,
                PETSC_COMM_WORLD, &requests_[n + k]);
    }
    MPI_Waitall(static_cast<int>(n), requests_.data(), MPI_STATUSES_IGNORE);
    for (auto& nb : neighbours_) add(nb.mine_buffer.data(), nb.mine, a);
    MPI_Waitall(static_cast<int>(n), requests_.data() + n, MPI_STATUSES_IGNORE);
    // 2. the owners' sums back to the ghosts
    for (std::size_t k = 0; k < n; ++k) {
      auto& nb = neighbours_[k];
      MPI_Irecv(nb.theirs_buffer.data(), static_cast<int>(nb.theirs_buffer.size()), MPI_DOUBLE, nb.rank, 2,
                PETSC_COMM_WORLD, &requests_[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      auto& nb = neighbours_[k];
      pack(a, nb.mine, nb.mine_buffer.data());
      MPI_Isend(nb.mine_buffer.data(), static_cast<int>(nb.mine_buffer.size()), MPI_DOUBLE, nb.rank, 2,
                PETSC_COMM_WORLD, &requests_[n + k]);
    }
    MPI_Waitall(static_cast<int>(n), requests_.data(), MPI_STATUSES_IGNORE);
    for (auto& nb : neighbours_) unpack(nb.theirs_buffer.data(), nb.theirs, a);
    MPI_Waitall(static_cast<int>(n), requests_.data() + n, MPI_STATUSES_IGNORE);
  }

  /// Doubles this rank sends per exchange (both phases).
  [[nodiscard]] long doubles_sent() const {
    long s = 0;
    for (const auto& nb : neighbours_) s += static_cast<long>(nb.theirs_buffer.size() + nb.mine_buffer.size());
    return s;
  }

 private:
  struct Neighbour {
    int rank;
    Box theirs, mine;
    std::vector<double> theirs_buffer, mine_buffer;
  };

  void pack(const double* a, const Box& strip, double* out) const {
    const PetscInt row = strip.width() * kDof;
    for (PetscInt j = strip.y0; j < strip.y1; ++j, out += row) std::copy_n(a + offset(box_, strip.x0, j), row, out);
  }
  void unpack(const double* in, const Box& strip, double* a) const {
    const PetscInt row = strip.width() * kDof;
    for (PetscInt j = strip.y0; j < strip.y1; ++j, in += row) std::copy_n(in, row, a + offset(box_, strip.x0, j));
  }
  void add(const double* in, const Box& strip, double* a) const {
    const PetscInt row = strip.width() * kDof;
    for (PetscInt j = strip.y0; j < strip.y1; ++j, in += row) {
      double* to = a + offset(box_, strip.x0, j);
      for (PetscInt k = 0; k < row; ++k) to[k] += in[k];
    }
  }

  Box box_;
  std::vector<Neighbour> neighbours_;
  std::vector<MPI_Request> requests_;
};

/// PetscSF over the same ghosted arrays: leaves are my ghost nodes, roots their owners' nodes (at
/// their offsets in the owners' ghosted arrays); the unit is kDof contiguous doubles.
PetscSF make_sf(const Partition& part, int me) {
  const Box box = part.ghosted(me), owned = part.owned(me);
  std::vector<PetscInt> local;
  std::vector<PetscSFNode> remote;
  for (PetscInt j = box.y0; j < box.y1; ++j)
    for (PetscInt i = box.x0; i < box.x1; ++i) {
      if (owned.contains(i, j)) continue;
      const int q = part.owner(i, j);
      local.push_back(offset(box, i, j) / kDof);
      remote.push_back({q, offset(part.ghosted(q), i, j) / kDof});
    }
  PetscSF sf;
  PetscSFCreate(PETSC_COMM_WORLD, &sf);
  PetscSFSetGraph(sf, box.nodes(), static_cast<PetscInt>(local.size()), local.data(), PETSC_COPY_VALUES,
                  remote.data(), PETSC_COPY_VALUES);
  PetscSFSetUp(sf);
  return sf;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Size {
  PetscInt N;
  int repetitions;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<Size> sizes;
  for (int k = 1; k < argc; ++k) {
    const std::string word = argv[k];
    const auto colon = word.find(':');
    sizes.push_back({static_cast<PetscInt>(std::atol(word.substr(0, colon).c_str())),
                     colon == std::string::npos ? 200 : std::atoi(word.substr(colon + 1).c_str())});
  }
  if (sizes.empty()) sizes = {{256, 2000}, {1024, 400}, {2048, 150}};
  // HALO_METHODS (optional): the methods to run, e.g. "mpi" or "dmda,sf"; the others print 0.
  bool use[3] = {true, true, true};
  if (const char* only = std::getenv("HALO_METHODS")) {
    const std::string list = only;
    use[0] = list.find("dmda") != std::string::npos;
    use[1] = list.find("mpi") != std::string::npos;
    use[2] = list.find("sf") != std::string::npos;
  }
  const bool percentiles = std::getenv("HALO_PERCENTILES") != nullptr;
  int no_args = 1;
  char* no_argv_storage[] = {argv[0], nullptr};
  char** no_argv = no_argv_storage;
  PetscCall(PetscInitialize(&no_args, &no_argv, nullptr, nullptr));  // PETSc must not parse our words
  int me = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &me);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  MPI_Datatype unit;
  MPI_Type_contiguous(kDof, MPI_DOUBLE, &unit);
  MPI_Type_commit(&unit);
  if (me == 0)
    std::printf("ranks %d, %d doubles per node; ms per exchange (median over repetitions, slowest rank)\n"
                "%6s %2s %5s %9s %9s %9s %9s %9s %9s %12s %s\n",
                ranks, kDof, "N", "g", "reps", "dmda", "mpi", "sf", "dmda min", "mpi min", "sf min",
                "halo KB/rank", "check");
  bool all_ok = true;
  for (const Size& size : sizes)
    for (PetscInt g : {1, 2}) {
      const PetscInt N = size.N;
      DM da;
      PetscCall(DMDACreate2d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, N, N,
                             PETSC_DECIDE, PETSC_DECIDE, kDof, g, nullptr, nullptr, &da));
      PetscCall(DMSetUp(da));
      Partition part;
      part.N = N, part.g = g;
      PetscCall(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, &part.m, &part.n, nullptr, nullptr, nullptr,
                            nullptr, nullptr, nullptr, nullptr));
      const PetscInt *lx, *ly;
      PetscCall(DMDAGetOwnershipRanges(da, &lx, &ly, nullptr));
      part.xcut.assign(1, 0);
      for (PetscInt a = 0; a < part.m; ++a) part.xcut.push_back(part.xcut.back() + lx[a]);
      part.ycut.assign(1, 0);
      for (PetscInt b = 0; b < part.n; ++b) part.ycut.push_back(part.ycut.back() + ly[b]);
      // the DMDA's ghosted box must be the one the check and the other two methods assume
      PetscInt gxs, gys, gxm, gym;
      PetscCall(DMDAGetGhostCorners(da, &gxs, &gys, nullptr, &gxm, &gym, nullptr));
      const Box box = part.ghosted(me);
      if (gxs != box.x0 || gys != box.y0 || gxm != box.width() || gym != box.y1 - box.y0) {
        std::fprintf(stderr, "rank %d: the DMDA's ghosted box differs from the partition's\n", me);
        MPI_Abort(PETSC_COMM_WORLD, 1);
      }

      Vec local, global;
      PetscCall(DMCreateLocalVector(da, &local));
      PetscCall(DMCreateGlobalVector(da, &global));
      std::vector<double> plain(box.nodes() * kDof), sf_array(box.nodes() * kDof);
      PlainExchange mpi(part, me);
      PetscSF sf = make_sf(part, me);

      const int warm_up = 5;
      std::vector<double> t_dmda, t_mpi, t_sf;
      long wrong[3] = {0, 0, 0};
      for (int rep = -warm_up; rep < size.repetitions; ++rep) {
        double t[3];
        t[0] = t[1] = t[2] = 0.0;
        if (use[0]) {  // dmda
          PetscScalar* a;
          PetscCall(VecGetArray(local, &a));
          fill(a, box.nodes());
          PetscCall(VecRestoreArray(local, &a));
          MPI_Barrier(PETSC_COMM_WORLD);
          const double t0 = MPI_Wtime();
          PetscCall(VecZeroEntries(global));
          PetscCall(DMLocalToGlobalBegin(da, local, ADD_VALUES, global));
          PetscCall(DMLocalToGlobalEnd(da, local, ADD_VALUES, global));
          PetscCall(DMGlobalToLocalBegin(da, global, INSERT_VALUES, local));
          PetscCall(DMGlobalToLocalEnd(da, global, INSERT_VALUES, local));
          t[0] = MPI_Wtime() - t0;
          if (rep == 0) {
            const PetscScalar* r;
            PetscCall(VecGetArrayRead(local, &r));
            wrong[0] = check(part, me, r);
            PetscCall(VecRestoreArrayRead(local, &r));
          }
        }
        if (use[1]) {  // plain MPI
          fill(plain.data(), box.nodes());
          MPI_Barrier(PETSC_COMM_WORLD);
          const double t0 = MPI_Wtime();
          mpi.exchange(plain.data());
          t[1] = MPI_Wtime() - t0;
          if (rep == 0) wrong[1] = check(part, me, plain.data());
        }
        if (use[2]) {  // PetscSF on the same arrays
          fill(sf_array.data(), box.nodes());
          double* a = sf_array.data();
          MPI_Barrier(PETSC_COMM_WORLD);
          const double t0 = MPI_Wtime();
          PetscCall(PetscSFReduceBegin(sf, unit, a, a, MPI_SUM));
          PetscCall(PetscSFReduceEnd(sf, unit, a, a, MPI_SUM));
          PetscCall(PetscSFBcastBegin(sf, unit, a, a, MPI_REPLACE));
          PetscCall(PetscSFBcastEnd(sf, unit, a, a, MPI_REPLACE));
          t[2] = MPI_Wtime() - t0;
          if (rep == 0) wrong[2] = check(part, me, sf_array.data());
        }
        MPI_Allreduce(MPI_IN_PLACE, t, 3, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
        if (rep >= 0) {
          t_dmda.push_back(1e3 * t[0]);
          t_mpi.push_back(1e3 * t[1]);
          t_sf.push_back(1e3 * t[2]);
        }
      }
      MPI_Allreduce(MPI_IN_PLACE, wrong, 3, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
      long sent = mpi.doubles_sent();
      MPI_Allreduce(MPI_IN_PLACE, &sent, 1, MPI_LONG, MPI_MAX, PETSC_COMM_WORLD);
      const bool ok = wrong[0] == 0 && wrong[1] == 0 && wrong[2] == 0;
      all_ok = all_ok && ok;
      if (me == 0) {
        std::printf("%6ld %2ld %5d %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f %12.1f %s",
                    static_cast<long>(N), static_cast<long>(g), size.repetitions, median(t_dmda), median(t_mpi),
                    median(t_sf), *std::min_element(t_dmda.begin(), t_dmda.end()),
                    *std::min_element(t_mpi.begin(), t_mpi.end()), *std::min_element(t_sf.begin(), t_sf.end()),
                    8.0 * static_cast<double>(sent) / 1024.0, ok ? "ok" : "WRONG");
        if (!ok) std::printf(" (wrong nodes: dmda %ld, mpi %ld, sf %ld)", wrong[0], wrong[1], wrong[2]);
        std::printf("\n");
        if (percentiles) {  // HALO_PERCENTILES=1: the distribution (a loaded machine skews the median)
          const char* names[3] = {"dmda", "mpi", "sf"};
          const std::vector<double>* times[3] = {&t_dmda, &t_mpi, &t_sf};
          for (int k = 0; k < 3; ++k) {
            if (!use[k]) continue;
            std::vector<double> v = *times[k];
            std::sort(v.begin(), v.end());
            const auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
            std::printf("       %-4s p10 %.4f p25 %.4f p50 %.4f p75 %.4f p90 %.4f max %.4f\n", names[k], at(0.1),
                        at(0.25), at(0.5), at(0.75), at(0.9), v.back());
          }
        }
        std::fflush(stdout);
      }
      PetscCall(PetscSFDestroy(&sf));
      PetscCall(VecDestroy(&local));
      PetscCall(VecDestroy(&global));
      PetscCall(DMDestroy(&da));
    }
  MPI_Type_free(&unit);
  PetscCall(PetscFinalize());
  return all_ok ? 0 : 1;
}
