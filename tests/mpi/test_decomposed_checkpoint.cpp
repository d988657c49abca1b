// Issue 23, per-rank checkpoints (docs/scale-out.md §9): a decomposed run stopped at a step and
// continued from its checkpoint equals the uninterrupted run bit for bit (each rank's particles in
// the same storage order, the history, the output pieces); only the last two checkpoints' pieces
// stay; a run killed between the new pieces and the new manifest leaves the previous set
// complete; a checkpoint of P ranks continues on 1 rank, and one of 1 rank on P, with every particle
// bit for bit; a damaged piece of one rank is refused on every rank.
//
// The expected values are the uninterrupted run's own: equality to the last bit is the claim. On
// one rank (mpi.petsc_solver.ranks1) the same tests run the one-rank checkpoint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/explicit_solver.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/hdf5_file.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/run/run_loop.hpp"
#include "matpoint/run/runner.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;
namespace fs = std::filesystem;

// Sulsky's two disks on the grid of test_decomposed_run.cpp (h = 0.02, 2528 particles, 7 brick
// layers along y), 600 steps: the lower disk's top crosses y = 0.48 at t = 0.3 (a slab boundary on
// 2 ranks), so particles arrive on the upper rank between the re-sorts, ahead of its own in the
// (key, id) order. MUSL, FLIP, quadratic B-splines; a checkpoint every 40 steps, outputs every 50;
// re-partitioned at the slightest imbalance every 10 steps (on 4 ranks the boxes follow the disks),
// so that a restart must continue the re-partitions where the uninterrupted run makes them.
const std::string kTwoDisks = R"({
  "grid": { "dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.02 },
  "materials": [ { "name": "elastic", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3 } ],
  "bodies": [
    { "name": "lower-left", "material": "elastic", "shape": { "type": "disk", "center": [0.25, 0.25], "radius": 0.2 },
      "particles_per_cell": 2, "velocity": [0.1, 0.1] },
    { "name": "upper-right", "material": "elastic", "shape": { "type": "disk", "center": [0.75, 0.75], "radius": 0.2 },
      "particles_per_cell": 2, "velocity": [-0.1, -0.1] } ],
  "solver": { "scheme": "musl", "transfer": "flip", "basis": "bspline2", "dt": 0.001, "end_time": 3.0,
              "max_steps": 600, "rebalance": { "imbalance": 1.0001, "min_steps": 10 } },
  "output": { "every_steps": 50, "plots": false, "checkpoint": { "every_steps": 40 } }
})";

/// A folder every rank names alike, empty (rank 0 makes it; the others wait).
fs::path scratch(const std::string& tag, const Communicator& comm) {
  const fs::path dir =
      fs::temp_directory_path() / ("matpoint_mpi_checkpoint_" + tag + "_p" + std::to_string(comm.size()));
  if (comm.rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  comm.barrier();
  return dir;
}

RunResult run_in(const Spec& spec, const fs::path& dir, const fs::path& restart = {}) {
  RunOptions options;
  options.out_dir = dir;
  options.progress = false;
  options.threads = 1;
  options.restart = restart;
  return run_explicit(spec, options);
}

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// This rank's particles at `step` of the run in `dir`: its piece (one rank: the checkpoint).
fs::path state_file(const fs::path& dir, long step, const Communicator& comm) {
  return comm.distributed() ? dir / checkpoint_piece_name(step, comm.rank()) : dir / kCheckpointFile;
}

long piece_files(const fs::path& dir) {
  long n = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    n += entry.path().filename().string().starts_with("checkpoint.s") ? 1 : 0;
  return n;
}

/// Every dataset of this rank's part of two checkpoints at `step` is equal bit for bit; returns the
/// number of values that differ (0: equal), summed over the ranks.
long differing_values(const fs::path& a, const fs::path& b, long step, const Communicator& comm) {
  const Hdf5Reader x(state_file(a, step, comm)), y(state_file(b, step, comm));
  long differing = 0;
  EXPECT_EQ(x.integer("simulation/step"), step);
  EXPECT_EQ(y.integer("simulation/step"), step);
  for (const char* name :
       {"particles/x", "particles/v", "particles/F", "particles/stress", "particles/L", "particles/mass",
        "simulation/time", "simulation/external_impulse", "simulation/external_work",
        "simulation/grid_momentum_difference", "run/total_mass"}) {
    const auto shape = x.shape(name);
    EXPECT_EQ(shape, y.shape(name)) << name;
    if (shape != y.shape(name)) return 1;
    const auto u = x.doubles(name, shape), v = y.doubles(name, shape);
    for (std::size_t k = 0; k < u.size(); ++k) differing += u[k] != v[k] ? 1 : 0;
  }
  std::vector<const char*> integers{"particles/id"};  // the storage order
  if (comm.distributed()) integers.push_back("parallel/sort_keys");
  for (const char* name : integers) {
    const auto shape = x.shape(name);
    EXPECT_EQ(shape, y.shape(name)) << name;
    if (shape != y.shape(name)) return 1;
    const auto u = x.int64s(name, shape), v = y.int64s(name, shape);
    for (std::size_t k = 0; k < u.size(); ++k) differing += u[k] != v[k] ? 1 : 0;
  }
  if (comm.distributed()) {
    EXPECT_EQ(x.integer("parallel/sorted_prefix"), y.integer("parallel/sorted_prefix"));
  }
  return comm.sum(differing);
}

/// The end of a continued run: its particles, history and outputs are the uninterrupted run's.
void expect_same_run(const fs::path& whole, const fs::path& parts, const RunResult& reference,
                     const RunResult& rest, const Communicator& comm, const std::string& what) {
  ASSERT_EQ(rest.exit_code, 0) << rest.message;
  EXPECT_EQ(rest.summary["steps"], reference.summary["steps"]);
  EXPECT_EQ(rest.summary["outputs"], reference.summary["outputs"]);
  if (comm.distributed()) {  // solver.rebalance's count and steps continue (run/repartitions)
    EXPECT_EQ(rest.summary["parallel"]["repartitions"], reference.summary["parallel"]["repartitions"]);
    if (comm.rank() == 0)
      std::printf("%s: %ld re-partitions\n", what.c_str(),
                  reference.summary["parallel"]["repartitions"].get<long>());
  }
  const long steps = reference.summary["steps"].get<long>();
  const long differing = differing_values(whole, parts, steps, comm);
  EXPECT_EQ(differing, 0) << what << ": values that differ from the uninterrupted run's";
  // the history's rows (full precision in the manifest; rank 0 wrote history.csv) and outputs
  EXPECT_TRUE(file_text(whole / "history.csv") == file_text(parts / "history.csv"))
      << what << ": history.csv";
  EXPECT_TRUE(file_text(whole / "results.pvd") == file_text(parts / "results.pvd"))
      << what << ": results.pvd";
  const Hdf5Reader x(whole / kCheckpointFile), y(parts / kCheckpointFile);
  const auto shape = x.shape("history/samples");
  ASSERT_EQ(shape, y.shape("history/samples"));
  EXPECT_TRUE(x.doubles("history/samples", shape) == y.doubles("history/samples", shape))
      << what << ": history/samples";
  char name[64];
  const long last = reference.summary["outputs"].get<long>() - 1;
  if (comm.distributed())
    std::snprintf(name, sizeof name, "particles_%06ld_r%04d.vtu", last, comm.rank());
  else
    std::snprintf(name, sizeof name, "particles_%06ld.vtu", last);
  EXPECT_TRUE(file_text(whole / name) == file_text(parts / name)) << what << ": " << name;
  if (comm.rank() == 0)
    std::printf(
        "%s on %d rank(s): %ld steps, %zu history rows; %ld values differ from the uninterrupted run\n",
        what.c_str(), comm.size(), steps, static_cast<std::size_t>(shape[0]), differing);
}

/// The whole run (to max_steps), the same run stopped at `stop` and continued from its checkpoint,
/// and continued from the checkpoint before (`previous`) as after a kill between the new pieces and
/// the new manifest.
void expect_restarts_bit_for_bit(const std::string& tag, const std::string& json, long stop, long previous,
                                 bool check_arrivals) {
  const Communicator comm = Communicator::world();
  const Spec spec = parse_spec(json);
  const fs::path whole = scratch(tag + "_whole", comm), parts = scratch(tag + "_parts", comm),
                 killed = scratch(tag + "_killed", comm);

  const RunResult reference = run_in(spec, whole);
  ASSERT_EQ(reference.exit_code, 0) << reference.message;
  ASSERT_EQ(reference.summary["steps"].get<long>(), spec.solver.max_steps);

  Spec first = spec;
  first.solver.max_steps = stop;  // a finished run with checkpoints enabled writes a final checkpoint
  const RunResult stopped = run_in(first, parts);
  ASSERT_EQ(stopped.exit_code, 0) << stopped.message;
  ASSERT_EQ(stopped.summary["checkpoint_step"].get<long>(), stop);
  // The pieces of the last two checkpoints stay, the older ones are gone.
  comm.barrier();
  const long pieces = comm.distributed() ? 2L * comm.size() : 0L;
  EXPECT_EQ(piece_files(parts), pieces);
  EXPECT_EQ(piece_files(whole), pieces);
  if (comm.distributed()) {
    EXPECT_TRUE(fs::exists(parts / checkpoint_piece_name(previous, comm.rank())));
    EXPECT_TRUE(fs::exists(parts / checkpoint_piece_name(stop, comm.rank())));
    // The particles that arrived since the last sort: their order is what the sort keys restore.
    const Hdf5Reader piece(parts / checkpoint_piece_name(stop, comm.rank()));
    const long arrived = comm.sum(static_cast<long>(piece.shape("particles/id")[0]) -
                                  static_cast<long>(piece.integer("parallel/sorted_prefix")));
    if (comm.rank() == 0)
      std::printf("%s: %ld particles arrived on other ranks since the last sort\n", tag.c_str(), arrived);
    if (check_arrivals) {
      EXPECT_GT(arrived, 0) << "the restart must fall where particles arrived since the last sort";
    }
  }

  // A run killed after writing the pieces of step `stop` but before its manifest replaced the one
  // of step `previous`: checkpoint.h5 is still that one (now checkpoint.previous.h5), and no
  // summary.json.
  if (comm.rank() == 0) {
    fs::copy(parts, killed, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    fs::rename(killed / kPreviousCheckpointFile, killed / kCheckpointFile);
    fs::remove(killed / "summary.json");
  }
  comm.barrier();

  const RunResult rest = run_in(spec, parts, parts / kCheckpointFile);
  EXPECT_EQ(rest.summary["restarted_at_step"].get<long>(), stop);
  expect_same_run(whole, parts, reference, rest, comm, tag + ", restart at the last checkpoint");

  const RunResult after_kill = run_in(spec, killed, killed / kCheckpointFile);
  EXPECT_EQ(after_kill.summary["restarted_at_step"].get<long>(), previous);
  expect_same_run(whole, killed, reference, after_kill, comm,
                  tag + ", restart at the checkpoint before, after a killed write");
}

TEST(DecomposedCheckpoint, TwoDisksContinueBitForBitAndAKilledWriteLeavesTheSetBefore) {
  // 453: between the re-sorts (every 10 steps) and the checkpoints (every 40)
  expect_restarts_bit_for_bit("disks", kTwoDisks, 453, 440, /*check_arrivals=*/true);
}

// The Mohr-Coulomb column of test_decomposed_run.cpp (uGIMP, USL, gravity: the ranks' own total
// mass and impulse; the material state; a fixed floor and a slip wall), 240 steps.
TEST(DecomposedCheckpoint, MohrCoulombColumnContinuesBitForBit) {
  const std::string json = R"({
    "grid": { "dim": 2, "min": [0, 0], "max": [4, 2.2], "cell_size": 0.05 },
    "materials": [ { "name": "soil", "model": "mohr_coulomb", "density": 1850, "E": 1.8e6, "nu": 0.3,
                     "cohesion": 5000, "friction_angle": 25, "dilation_angle": 0 } ],
    "bodies": [ { "name": "column", "material": "soil", "shape": { "type": "box", "min": [0, 0], "max": [1, 2] },
                  "particles_per_cell": 2 } ],
    "boundary_conditions": [ { "face": "y-", "type": "fixed" }, { "face": "x-", "type": "slip" } ],
    "loads": { "gravity": [0, -9.81] },
    "solver": { "scheme": "usl", "transfer": "flip", "basis": "ugimp", "courant": 0.5, "end_time": 2.0,
                "max_steps": 240 },
    "output": { "every_steps": 40, "plots": false, "checkpoint": { "every_steps": 30 } }
  })";
  expect_restarts_bit_for_bit("column", json, 137, 120, /*check_arrivals=*/false);
}

/// Every particle of a checkpoint (the pieces its manifest names, or the one-rank file) by id: x,
/// v, F, stress, L and the material state.
std::map<long, std::vector<double>> particles_by_id(const fs::path& checkpoint) {
  std::vector<fs::path> files{checkpoint};
  const Hdf5Reader manifest(checkpoint);
  if (manifest.has("parallel/pieces")) {
    files.clear();
    std::istringstream names(manifest.text("parallel/pieces"));
    for (std::string name; std::getline(names, name);) files.push_back(checkpoint.parent_path() / name);
  }
  std::map<long, std::vector<double>> out;
  for (const auto& file : files) {
    const Hdf5Reader r(file);
    const auto ids = r.int64s("particles/id", r.shape("particles/id"));
    std::vector<std::vector<double>> arrays;
    for (const char* name :
         {"particles/x", "particles/v", "particles/F", "particles/stress", "particles/L", "particles/state"})
      arrays.push_back(r.doubles(name, r.shape(name)));
    for (std::size_t p = 0; p < ids.size(); ++p) {
      auto& values = out[ids[p]];
      EXPECT_TRUE(values.empty()) << "particle " << ids[p] << " twice";
      for (const auto& array : arrays) {
        const std::size_t width = array.size() / ids.size();
        values.insert(values.end(), array.begin() + static_cast<std::ptrdiff_t>(p * width),
                      array.begin() + static_cast<std::ptrdiff_t>((p + 1) * width));
      }
    }
  }
  return out;
}

/// The run continued on other ranks than it was written on equals the uninterrupted run: every
/// particle bit for bit, the history (sums over other ranks: round-off) to 1e-12 of its largest value.
void expect_same_particles(const fs::path& reference, const fs::path& continued, const std::string& what) {
  const auto a = particles_by_id(reference), b = particles_by_id(continued);
  ASSERT_EQ(a.size(), b.size()) << what;
  long differing = 0;
  for (const auto& [id, values] : a) {
    const auto found = b.find(id);
    ASSERT_NE(found, b.end()) << what << ": particle " << id << " is missing";
    ASSERT_EQ(found->second.size(), values.size());
    for (std::size_t k = 0; k < values.size(); ++k) differing += values[k] != found->second[k] ? 1 : 0;
  }
  EXPECT_EQ(differing, 0) << what << ": particle values that differ from the uninterrupted run's";
  const Hdf5Reader x(reference), y(continued);
  const auto shape = x.shape("history/samples");
  ASSERT_EQ(shape, y.shape("history/samples")) << what;
  const auto u = x.doubles("history/samples", shape), v = y.doubles("history/samples", shape);
  double largest = 0.0, worst = 0.0;
  for (const double value : u) largest = std::max(largest, std::abs(value));
  for (std::size_t k = 0; k < u.size(); ++k) {
    const std::size_t column = k % shape[1];
    if (column <= 1) {
      EXPECT_EQ(u[k], v[k]) << what << ": time and step are exact";
    }
    worst = std::max(worst, std::abs(u[k] - v[k]));
  }
  EXPECT_LE(worst, 1e-12 * largest) << what << ": history";
  std::printf("%s: %zu particles, %ld values differ; history within %.1e of its largest value\n",
              what.c_str(), a.size(), differing, worst / largest);
}

RunResult run_on_one_rank(const Spec& spec, const fs::path& dir, const fs::path& restart = {}) {
  RunOptions options;
  options.out_dir = dir;
  options.progress = false;
  options.threads = 1;
  options.restart = restart;
  ExplicitSolver<2, TensorStencils<2, QuadraticBSplineBasis>> solver(spec, Communicator());
  return run_loop<2>(spec, options, solver);
}

// A checkpoint of P ranks continued on 1, and one of 1 rank continued on P: every rank reads every
// piece, the partition is balanced anew, and each rank keeps its cells' particles in (sort key, id)
// order, the order in which every rank count sums a brick's particles.
TEST(DecomposedCheckpoint, CheckpointOfAnotherRankCountContinuesBitForBit) {
  const Communicator comm = Communicator::world();
  if (!comm.distributed()) GTEST_SKIP() << "needs several ranks";
  const Spec spec = parse_spec(kTwoDisks);
  Spec first = spec;
  first.solver.max_steps = 453;
  const fs::path whole = scratch("other_whole", comm), parts = scratch("other_parts", comm),
                 one = scratch("other_one", comm), serial = scratch("other_serial", comm);
  ASSERT_EQ(run_in(spec, whole).exit_code, 0);
  ASSERT_EQ(run_in(first, parts).exit_code, 0);
  comm.barrier();
  if (comm.rank() == 0) {  // P ranks -> 1
    fs::copy(parts, one, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    const RunResult rest = run_on_one_rank(spec, one, one / kCheckpointFile);
    EXPECT_EQ(rest.exit_code, 0) << rest.message;
    const RunResult stopped = run_on_one_rank(first, serial);  // 1 rank, to step 453
    EXPECT_EQ(stopped.exit_code, 0) << stopped.message;
  }
  comm.barrier();
  const RunResult rest = run_in(spec, serial, serial / kCheckpointFile);  // 1 -> P ranks
  ASSERT_EQ(rest.exit_code, 0) << rest.message;
  comm.barrier();
  if (comm.rank() == 0) {
    expect_same_particles(whole / kCheckpointFile, one / kCheckpointFile,
                          std::to_string(comm.size()) + " ranks continued on 1");
    expect_same_particles(whole / kCheckpointFile, serial / kCheckpointFile,
                          "1 rank continued on " + std::to_string(comm.size()));
  }
  comm.barrier();
}

// output.checkpoint.every_minutes reads a wall clock per process: rank 0's decides, carried by the
// step's collective. Here only rank 0's schedule makes a checkpoint due (after every step; the
// others' is once in 1e9 minutes): every rank must write its piece at every step, or the run
// would hang in the pieces' collective.
TEST(DecomposedCheckpoint, WallClockCheckpointIsRankZerosDecision) {
  const Communicator comm = Communicator::world();
  if (!comm.distributed()) GTEST_SKIP() << "needs several ranks";
  Spec spec = parse_spec(kTwoDisks);
  spec.solver.max_steps = 5;
  spec.output.checkpoint = {0, comm.rank() == 0 ? 1e-12 : 1e9};
  const fs::path dir = scratch("minutes", comm);
  const RunResult result = run_in(spec, dir);
  ASSERT_EQ(result.exit_code, 0) << result.message;
  EXPECT_EQ(result.summary["checkpoint_step"], 5);
  comm.barrier();
  EXPECT_EQ(Hdf5Reader(dir / kCheckpointFile).integer("simulation/step"), 5);
  EXPECT_EQ(Hdf5Reader(dir / kPreviousCheckpointFile).integer("simulation/step"), 4);
  EXPECT_TRUE(fs::exists(dir / checkpoint_piece_name(4, comm.rank())));
  EXPECT_EQ(piece_files(dir), 2L * comm.size()) << "the pieces of steps 1 to 3 are deleted";
  comm.barrier();
}

/// Every rank reads; one rank's damaged piece makes every rank throw the same InputError (none is
/// left waiting in the run's first collective).
TEST(DecomposedCheckpoint, DamagedPieceOfOneRankIsRefusedOnEveryRank) {
  const Communicator comm = Communicator::world();
  if (!comm.distributed()) GTEST_SKIP() << "needs several ranks";
  Spec spec = parse_spec(kTwoDisks);
  spec.solver.max_steps = 12;
  const fs::path dir = scratch("damaged", comm);
  ASSERT_EQ(run_in(spec, dir).exit_code, 0);
  comm.barrier();
  const int last = comm.size() - 1;
  const fs::path piece = dir / checkpoint_piece_name(12, last);
  if (comm.rank() == 0) {
    const std::string text = file_text(piece);
    std::ofstream(piece, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() / 2);
    fs::remove(dir / "summary.json");
  }
  comm.barrier();
  if (comm.rank() == 0) {  // a piece is not a checkpoint to restart from
    Simulation<2> sim = build_simulation<2>(spec);
    RunCounters run;
    History history{2, 2, {}, {}, {}};
    try {
      read_checkpoint<2>(dir / checkpoint_piece_name(12, 0), spec.echo, sim, run, history);
      ADD_FAILURE() << "a piece was read as a checkpoint";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("one rank's piece"), std::string::npos) << e.what();
    }
  }
  Spec longer = spec;
  longer.solver.max_steps = 20;
  try {
    run_in(longer, dir, dir / kCheckpointFile);
    ADD_FAILURE() << "a damaged piece was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(piece.filename().string()), std::string::npos) << e.what();
    if (comm.rank() == 0) std::printf("refused on every rank: %s\n", e.what());
  }
  comm.barrier();
}

}  // namespace
