// Checkpoints: every array survives a write/read round trip bit for bit (1-D, 2-D, 3-D, CPDI2
// corners, material history, FMPM and output counters, history rows); a run continued from a
// checkpoint equals the uninterrupted run bit for bit (one thread); damaged files and checkpoints
// of another input are refused with an InputError (exit 2) that says why.
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>

#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/hdf5_file.hpp"
#include "matpoint/particles/remove_particles.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;
namespace fs = std::filesystem;

fs::path scratch(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("matpoint_checkpoint_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string input_text(int dim, const std::string& shape, const std::string& transfer) {
  const std::string v = dim == 1 ? "[0.3]" : dim == 2 ? "[0.3, -0.2]" : "[0.3, -0.2, 0.1]";
  const std::string lo = dim == 1 ? "[0]" : dim == 2 ? "[0, 0]" : "[0, 0, 0]";
  const std::string hi = dim == 1 ? "[1]" : dim == 2 ? "[1, 1]" : "[1, 1, 1]";
  const std::string box_lo = dim == 1 ? "[0.3]" : dim == 2 ? "[0.3, 0.3]" : "[0.3, 0.3, 0.3]";
  const std::string box_hi = dim == 1 ? "[0.7]" : dim == 2 ? "[0.7, 0.6]" : "[0.6, 0.6, 0.6]";
  return R"({"grid": {"dim": )" + std::to_string(dim) + R"(, "min": )" + lo + R"(, "max": )" + hi +
         R"(, "cell_size": 0.1},
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 1e5, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": )" +
         box_lo + R"(, "max": )" + box_hi + R"(}, "velocity": )" + v + R"(,
                "velocity_sine": {"amplitude": )" +
         v + R"(, "wave_vector": )" + v + R"(}}],
    "solver": {"scheme": "usavg", "transfer": )" +
         transfer + R"(, "basis": ")" + shape + R"(", "courant": 0.3, "end_time": 0.1},
    "output": {"every_steps": 5, "plots": false, "checkpoint": {"every_steps": 7}}})";
}

// --- round trip of every array ---

template <int D>
void fill(Simulation<D>& sim) {
  auto& ps = sim.particles;
  double k = 0.1234567890123;
  auto next = [&k] { return k = std::fmod(k * 7.31 + 0.377, 3.0) - 1.0; };
  for (std::size_t p = 0; p < ps.size(); ++p) {
    for (int a = 0; a < D; ++a) {
      ps.x[p][a] = 0.5 + 0.1 * next(), ps.v[p][a] = next(), ps.size0[p][a] = next();
      for (int b = 0; b < D; ++b) ps.F[p](a, b) = next(), ps.stress[p](a, b) = next(), ps.L[p](a, b) = next();
    }
    ps.mass[p] = next(), ps.volume0[p] = next();
    if (!ps.stress_zz.empty()) ps.stress_zz[p] = next();  // plane strain sigma_zz (2-D)
    if (!ps.corners.empty())
      for (auto& corner : ps.corners[p])
        for (int a = 0; a < D; ++a) corner[a] = next();
  }
  std::reverse(ps.id.begin(), ps.id.end());  // a storage order that is not the id order
  ps.material.assign(ps.size(), 0);
  ps.body.assign(ps.size(), 0);
  ps.state_stride = 2;  // material history: two values per particle
  ps.state.resize(2 * ps.size());
  for (double& s : ps.state) s = next();
  sim.time = 0.0123456789, sim.step = 1234567, sim.external_work = next();
  for (int a = 0; a < D; ++a) sim.external_impulse[a] = next();
  for (auto& x : ps.v0) x = Vec<D>::Constant(next());  // V_p(0), X_p: by storage index
  for (auto& x : ps.x0) x = Vec<D>::Constant(next());
  for (int a = 0; a < D; ++a) sim.grid_momentum_difference[a] = next();
}

RunCounters counters() {
  RunCounters run;
  run.dt = 1.1e-4, run.momentum_scale = 2.2, run.total_mass = 3.3, run.outputs = 4,
  run.next_output_time = 5.5;
  run.last_recorded_step = 66, run.next_fmpm_time = 7.7, run.fmpm_loops = 88, run.fmpm_passes = 99;
  run.fmpm_seconds = 0.1, run.step_wall = 1.2, run.step_cpu = 1.3, run.wall = 1.4, run.threads = 3;
  run.results = {{0.0, "particles_000000.vtu"}, {0.5, "particles_000001.vtu"}};
  run.domains = {{0.0, "domains_000000.vtu"}};
  return run;
}

History history_of(int dim, int bodies) {
  History h{dim, bodies, {}, {}, {}};
  for (int r = 0; r < 3; ++r) {
    HistorySample s;
    s.time = 0.1 * r + 1e-17, s.step = 10 * r, s.kinetic_energy = 1.0 / 3 + r, s.strain_energy = 2.0 / 7;
    s.external_work = -1.0 / 9, s.momentum = {1e-300, -2.5, 3}, s.external_impulse = {4, 5, 6};
    s.min_jacobian = 0.99, s.rms_velocity_change = 1e-12;
    s.grid_momentum_difference = {1e-17, -2e-17, 0}, s.checkerboard_velocity = 0.25 + r;
    s.grid_rms_velocity = 1.0 / 7, s.hourglass_energy = 1e-9, s.friction_work = 0.125 + r;
    s.plastic_work = 0.0625 + r;
    for (int b = 0; b < bodies; ++b) {
      s.body_kinetic.push_back(r + b + 0.1), s.body_strain.push_back(0.2), s.body_mass.push_back(0.3);
      s.body_momentum.push_back({1, 2, 3}), s.body_com_velocity.push_back({4, 5, 6.5});
      s.body_com_position.push_back({-1, 0.5, 7});
    }
    h.samples.push_back(s);
  }
  return h;
}

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <int D>
void round_trip(const std::string& shape, const std::string& transfer) {
  const Spec spec = parse_spec(input_text(D, shape, transfer));
  Simulation<D> written = build_simulation<D>(spec);
  fill(written);
  const RunCounters run = counters();
  const History history = history_of(D, 1);
  const fs::path dir = scratch("round_trip_" + std::to_string(D) + shape);
  write_checkpoint<D>(dir / kCheckpointFile, dir / kPreviousCheckpointFile, written, run, history, spec.echo);

  Simulation<D> read = build_simulation<D>(spec);
  RunCounters r;
  History h{D, 1, {}, {}, {}};
  read_checkpoint<D>(dir / kCheckpointFile, spec.echo, read, r, h);
  const auto& a = written.particles;
  const auto& b = read.particles;
  EXPECT_TRUE(same(a.x, b.x) && same(a.v, b.v) && same(a.size0, b.size0)) << D << "-D x, v, size0";
  EXPECT_TRUE(same(a.F, b.F) && same(a.stress, b.stress) && same(a.L, b.L)) << D << "-D F, stress, L";
  EXPECT_TRUE(same(a.mass, b.mass) && same(a.volume0, b.volume0));
  EXPECT_EQ(a.stress_zz.size(), D == 2 ? a.size() : 0u);
  EXPECT_TRUE(same(a.stress_zz, b.stress_zz)) << "plane-strain sigma_zz";
  EXPECT_TRUE(same(a.id, b.id) && same(a.material, b.material) && same(a.body, b.body));
  EXPECT_EQ(b.state_stride, 2);
  EXPECT_TRUE(same(a.state, b.state)) << "material history state";
  EXPECT_EQ(a.track_corners, b.track_corners);
  EXPECT_TRUE(same(a.corners, b.corners)) << "CPDI2 domain corners";
  EXPECT_EQ(read.time, written.time);
  EXPECT_EQ(read.step, written.step);
  EXPECT_EQ(read.external_work, written.external_work);
  EXPECT_EQ(read.external_impulse, written.external_impulse);
  EXPECT_EQ(read.grid_momentum_difference, written.grid_momentum_difference);
  EXPECT_TRUE(same(a.v0, b.v0) && same(a.x0, b.x0)) << "initial velocity and position";
  {  // the file keeps X_p and V_p(0) by particle id (docs/output.md), whatever the storage order
    const Hdf5Reader file(dir / kCheckpointFile);
    const hsize_t n = a.size();
    const auto X = file.doubles("simulation/initial_position", {n, D});
    const auto V = file.doubles("simulation/initial_velocity", {n, D});
    bool by_id = true;
    for (std::size_t p = 0; p < a.size(); ++p)
      for (int c = 0; c < D; ++c) {
        const auto k = static_cast<std::size_t>(a.id[p]) * D + c;
        by_id = by_id && X[k] == a.x0[p][c] && V[k] == a.v0[p][c];
      }
    EXPECT_TRUE(by_id) << "simulation/initial_position and initial_velocity by id";
  }
  EXPECT_EQ(r.dt, run.dt);
  EXPECT_EQ(r.momentum_scale, run.momentum_scale);
  EXPECT_EQ(r.total_mass, run.total_mass);
  EXPECT_EQ(r.outputs, run.outputs);
  EXPECT_EQ(r.next_output_time, run.next_output_time);
  EXPECT_EQ(r.last_recorded_step, run.last_recorded_step);
  EXPECT_EQ(r.next_fmpm_time, run.next_fmpm_time) << "periodic FMPM state";
  EXPECT_EQ(r.fmpm_loops, run.fmpm_loops);
  EXPECT_EQ(r.fmpm_passes, run.fmpm_passes);
  EXPECT_EQ(r.fmpm_seconds, run.fmpm_seconds);
  EXPECT_EQ(r.step_wall, run.step_wall);
  EXPECT_EQ(r.step_cpu, run.step_cpu);
  EXPECT_EQ(r.wall, run.wall);
  EXPECT_EQ(r.threads, run.threads);
  EXPECT_EQ(r.results, run.results);
  EXPECT_EQ(r.domains, run.domains);
  ASSERT_EQ(h.samples.size(), history.samples.size());
  for (std::size_t i = 0; i < h.samples.size(); ++i) {
    const auto &x = h.samples[i], &y = history.samples[i];
    EXPECT_EQ(x.time, y.time);
    EXPECT_EQ(x.step, y.step);
    EXPECT_EQ(x.kinetic_energy, y.kinetic_energy);
    EXPECT_EQ(x.strain_energy, y.strain_energy);
    EXPECT_EQ(x.external_work, y.external_work);
    EXPECT_EQ(x.momentum, y.momentum);
    EXPECT_EQ(x.external_impulse, y.external_impulse);
    EXPECT_EQ(x.min_jacobian, y.min_jacobian);
    EXPECT_EQ(x.rms_velocity_change, y.rms_velocity_change);
    EXPECT_EQ(x.grid_momentum_difference, y.grid_momentum_difference);
    EXPECT_EQ(x.checkerboard_velocity, y.checkerboard_velocity);
    EXPECT_EQ(x.grid_rms_velocity, y.grid_rms_velocity);
    EXPECT_EQ(x.hourglass_energy, y.hourglass_energy);
    EXPECT_EQ(x.body_kinetic, y.body_kinetic);
    EXPECT_EQ(x.body_strain, y.body_strain);
    EXPECT_EQ(x.body_mass, y.body_mass);
    EXPECT_EQ(x.body_momentum, y.body_momentum);
    EXPECT_EQ(x.body_com_velocity, y.body_com_velocity);
    EXPECT_EQ(x.body_com_position, y.body_com_position);
    EXPECT_EQ(x.friction_work, y.friction_work);
    EXPECT_EQ(x.plastic_work, y.plastic_work);
  }
  EXPECT_EQ(history.csv(), h.csv());
}

TEST(Checkpoint, RoundTripKeepsEveryArrayBitForBit1D) {
  round_trip<1>("cpdi1", R"("fmpm", "fmpm": {"order": 3, "periodic": {"time": 0.002}})");
}
TEST(Checkpoint, RoundTripKeepsEveryArrayBitForBit2D) { round_trip<2>("cpdi2", R"("flip")"); }
TEST(Checkpoint, RoundTripKeepsEveryArrayBitForBit3D) { round_trip<3>("cpdi2", R"("xpic")"); }

// The meshfree method's deletion repair (particles/remove_particles.hpp) leaves holes in the ids:
// the checkpoint keeps X_p and V_p(0) by id up to the largest one, and the survivors read back bit
// for bit, in their storage order.
TEST(Checkpoint, RoundTripAfterParticlesWereDeleted) {
  const Spec spec = parse_spec(input_text(2, "cpdi2", R"("flip")"));
  Simulation<2> written = build_simulation<2>(spec);
  fill(written);
  auto& a = written.particles;
  std::vector<char> gone(a.size(), 0);
  gone[0] = gone[3] = gone[a.size() - 1] = 1;  // storage 0 holds the largest id (fill reverses them)
  const long second = a.id[1];                 // the largest id left
  remove_particles(a, gone);
  ASSERT_EQ(a.id[0], second);
  const fs::path dir = scratch("round_trip_deleted");
  write_checkpoint<2>(dir / kCheckpointFile, dir / kPreviousCheckpointFile, written, counters(),
                      history_of(2, 1), spec.echo);
  EXPECT_EQ(Hdf5Reader(dir / kCheckpointFile).shape("simulation/initial_position")[0],
            static_cast<hsize_t>(second + 1));
  Simulation<2> read = build_simulation<2>(spec);
  RunCounters r;
  History h{2, 1, {}, {}, {}};
  read_checkpoint<2>(dir / kCheckpointFile, spec.echo, read, r, h);
  const auto& b = read.particles;
  ASSERT_EQ(b.size(), a.size());
  EXPECT_TRUE(same(a.id, b.id) && same(a.x, b.x) && same(a.v, b.v) && same(a.F, b.F) && same(a.mass, b.mass));
  EXPECT_TRUE(same(a.state, b.state) && same(a.corners, b.corners));
  EXPECT_TRUE(same(a.x0, b.x0) && same(a.v0, b.v0)) << "initial position and velocity by id";
}

// --- the checkpoint writes every array that for_each_array visits (particles/particle_set.hpp) ---

/// The names of the datasets in an HDF5 group.
std::set<std::string> datasets_in(const fs::path& file, const char* group) {
  std::set<std::string> names;
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_file_locking(access, false, true);  // as Hdf5Reader opens it
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, access);
  H5Pclose(access);
  const hid_t g = H5Gopen2(f, group, H5P_DEFAULT);
  H5G_info_t info;
  EXPECT_GE(H5Gget_info(g, &info), 0) << "group " << group << " of " << file;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    char name[256];
    H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
    names.insert(name);
  }
  H5Gclose(g);
  H5Fclose(f);
  return names;
}

/// The checkpoint keeps the particle arrays one dataset each (names of docs/output.md) and X_p,
/// V_p(0) by id as simulation/initial_position, initial_velocity. Each dataset with a row per
/// particle must be an array that for_each_array visits and each visited array must have its
/// dataset, so a particle array added to one and not the other fails here.
template <int D>
void expect_checkpoint_has_every_visited_array(const std::string& shape, const std::string& text) {
  const Spec spec = parse_spec(text);
  const Simulation<D> sim = build_simulation<D>(spec);
  ASSERT_GT(sim.particles.size(), 1u);
  const fs::path dir = scratch("visitor_" + std::to_string(D) + shape);
  write_checkpoint<D>(dir / kCheckpointFile, dir / kPreviousCheckpointFile, sim, counters(), history_of(D, 1),
                      spec.echo);
  std::set<std::string> visited;
  for_each_array(sim.particles, [&visited](const char* name, const auto&, std::size_t) {
    const std::string array(name);
    visited.insert(array == "x0"   ? "simulation/initial_position"
                   : array == "v0" ? "simulation/initial_velocity"
                                   : "particles/" + array);
  });
  const auto names = datasets_in(dir / kCheckpointFile, "particles");
  ASSERT_TRUE(names.count("x") == 1 && names.count("track_corners") == 1) << "the particles group is listed";
  const Hdf5Reader r(dir / kCheckpointFile);
  std::set<std::string> per_particle;  // the datasets with one row per particle
  for (const auto& name : names)
    if (r.shape("particles/" + name).front() == sim.particles.size())
      per_particle.insert("particles/" + name);
  for (const char* name : {"simulation/initial_position", "simulation/initial_velocity"})
    if (r.shape(name).front() == sim.particles.size()) per_particle.insert(name);
  EXPECT_EQ(per_particle, visited) << D << "-D " << shape;
}

TEST(Checkpoint, WritesEveryArrayThatForEachArrayVisits) {
  // 2-D CPDI2 with heat: every optional array (stress_zz, corners, temperature) in use.
  std::string text = input_text(2, "cpdi2", R"("flip")");
  const std::string nu = R"("nu": 0.3})";
  text.replace(text.find(nu), nu.size(), R"("nu": 0.3, "heat_capacity": 1000, "conductivity": 20})");
  text.insert(text.rfind('}'), R"(, "heat": {"initial_temperature": 300})");
  expect_checkpoint_has_every_visited_array<2>("cpdi2_heat", text);
  expect_checkpoint_has_every_visited_array<1>("linear", input_text(1, "linear", R"("flip")"));
  expect_checkpoint_has_every_visited_array<3>("cpdi2", input_text(3, "cpdi2", R"("xpic")"));
}

TEST(Checkpoint, SecondCheckpointKeepsThePreviousOne) {
  const Spec spec = parse_spec(input_text(2, "linear", R"("flip")"));
  Simulation<2> sim = build_simulation<2>(spec);
  const fs::path dir = scratch("previous");
  const History history = history_of(2, 1);
  sim.step = 1;
  write_checkpoint<2>(dir / kCheckpointFile, dir / kPreviousCheckpointFile, sim, counters(), history,
                      spec.echo);
  EXPECT_FALSE(fs::exists(dir / kPreviousCheckpointFile));
  sim.step = 2;
  write_checkpoint<2>(dir / kCheckpointFile, dir / kPreviousCheckpointFile, sim, counters(), history,
                      spec.echo);
  EXPECT_EQ(Hdf5Reader(dir / kCheckpointFile).integer("simulation/step"), 2);
  EXPECT_EQ(Hdf5Reader(dir / kPreviousCheckpointFile).integer("simulation/step"), 1);
  EXPECT_FALSE(fs::exists(dir / (std::string(kCheckpointFile) + ".partial")));
}

// --- restart equals the uninterrupted run ---

RunResult run_in(Spec spec, const fs::path& dir, const fs::path& restart = {}) {
  RunOptions options;
  options.out_dir = dir;
  options.progress = false;
  options.threads = 1;
  options.restart = restart;
  return run_explicit(spec, options);
}

/// Every particle dataset and the time of two checkpoints agree bit for bit.
void expect_same_state(const fs::path& a, const fs::path& b) {
  const Hdf5Reader x(a), y(b);
  EXPECT_EQ(x.number("simulation/time"), y.number("simulation/time"));
  EXPECT_EQ(x.integer("simulation/step"), y.integer("simulation/step"));
  for (const char* name : {"particles/x", "particles/v", "particles/F", "particles/stress", "particles/L",
                           "particles/corners", "particles/temperature", "simulation/external_impulse",
                           "simulation/external_work", "simulation/boundary_heat"}) {
    ASSERT_EQ(x.shape(name), y.shape(name)) << name;
    EXPECT_TRUE(same(x.doubles(name, x.shape(name)), y.doubles(name, y.shape(name)))) << name << " differs";
  }
  EXPECT_TRUE(same(x.int64s("particles/id", x.shape("particles/id")),
                   y.int64s("particles/id", y.shape("particles/id"))))
      << "storage order (sorting) differs";
}

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The whole run, then the same run stopped by `stop` and continued from its checkpoint.
template <class Stop>
void expect_restart_equals_uninterrupted(const std::string& tag, const Spec& spec, Stop stop) {
  const fs::path whole = scratch(tag + "_whole"), parts = scratch(tag + "_parts");
  const RunResult reference = run_in(spec, whole);
  ASSERT_EQ(reference.exit_code, 0) << reference.message;
  const RunResult first = stop(parts);
  ASSERT_TRUE(fs::exists(parts / kCheckpointFile));
  const long stopped_at = first.summary["checkpoint_step"].get<long>();
  ASSERT_GT(stopped_at, 0);
  ASSERT_LT(stopped_at, reference.summary["steps"].get<long>());
  const RunResult rest = run_in(spec, parts, parts / kCheckpointFile);
  ASSERT_EQ(rest.exit_code, 0) << rest.message;
  EXPECT_EQ(rest.summary["steps"], reference.summary["steps"]);
  EXPECT_EQ(rest.summary["outputs"], reference.summary["outputs"]);
  expect_same_state(whole / kCheckpointFile, parts / kCheckpointFile);
  // history.csv and results.pvd continue without a missing or repeated row; the .vtu files match.
  EXPECT_EQ(file_text(whole / "history.csv"), file_text(parts / "history.csv"));
  EXPECT_EQ(file_text(whole / "results.pvd"), file_text(parts / "results.pvd"));
  const long last = reference.summary["outputs"].get<long>() - 1;
  char name[48];
  std::snprintf(name, sizeof name, "particles_%06ld.vtu", last);
  EXPECT_EQ(file_text(whole / name), file_text(parts / name)) << name;
  EXPECT_EQ(rest.summary["checks_pass"], reference.summary["checks_pass"]);
}

TEST(Restart, RunStoppedByMaxStepsContinuesBitForBit) {
  // Periodic FMPM and CPDI2 corners: state beyond the particle arrays that a restart must keep;
  // 23 steps: between the re-sorts (every 10) and the scheduled checkpoints (every 7).
  Spec spec =
      parse_spec(input_text(2, "cpdi2", R"("fmpm", "fmpm": {"order": 3, "periodic": {"time": 0.0015}})"));
  expect_restart_equals_uninterrupted("max_steps", spec, [&](const fs::path& dir) {
    Spec first = spec;
    first.solver.max_steps = 23;  // a finished run with checkpoints enabled writes a final checkpoint
    return run_in(first, dir);
  });
}

TEST(Restart, HeatRunContinuesBitForBit) {
  // Coupled heat conduction: particle temperatures (a sine mode conducted with transport FMPM(3),
  // thermal expansion and thermoelastic heating) continue bit for bit.
  std::string text = input_text(2, "bspline2", R"("flip")");
  const std::string nu = R"("nu": 0.3})";
  text.replace(text.find(nu), nu.size(),
               R"("nu": 0.3, "heat_capacity": 1000, "conductivity": 20, "thermal_expansion": 1e-4})");
  text.insert(text.rfind('}'), R"(, "heat": {"transfer": "fmpm", "fmpm_order": 3,
      "temperature_sine": {"amplitude": 5, "wave_vector": [3, 2]}})");
  const Spec spec = parse_spec(text);
  expect_restart_equals_uninterrupted("heat", spec, [&](const fs::path& dir) {
    Spec first = spec;
    first.solver.max_steps = 23;
    return run_in(first, dir);
  });
}

TEST(Restart, InterruptedRunWritesACheckpointAndContinuesBitForBit) {
  // Checkpoints are scheduled every 7 steps: the one at step 1 is the interrupt's own.
  const Spec spec = parse_spec(input_text(2, "bspline2", R"("flip")"));
  expect_restart_equals_uninterrupted("interrupt", spec, [&](const fs::path& dir) {
    request_interrupt(SIGTERM);  // as if received during the first step
    const RunResult result = run_in(spec, dir);
    request_interrupt(0);
    EXPECT_EQ(result.exit_code, 128 + SIGTERM);
    EXPECT_EQ(result.summary["status"], "interrupted");
    EXPECT_EQ(result.summary["checkpoint_step"], 1);
    EXPECT_NE(result.message.find("--restart"), std::string::npos) << result.message;
    return result;
  });
}

// An implicit run (Aulisa & Capodaglio particle-Newmark MPM): a soft disk dropped on the fixed
// bottom of a Q9 mesh, bouncing (active sets, flags and Newton iterations change from step to step),
// with adaptive steps. The checkpoint must carry the particle accelerations a^n, the host elements,
// the adaptive dt and the Newton totals, so the restart continues bit for bit; the history's Newton
// columns continue too (history.csv compared whole).
std::string implicit_input_text() {
  return R"({"mesh": {"element": "q9", "min": [0, 0], "max": [1, 1], "cells": [4, 4]},
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 2e5, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.5, 0.35], "radius": 0.2},
                "velocity": [0.2, -1]}],
    "boundary_conditions": [{"type": "fixed", "boundary": "bottom"}],
    "loads": {"gravity": [0, -9.81]},
    "solver": {"type": "implicit_mpm", "dt": 0.01, "end_time": 0.3,
               "implicit": {"soft_stiffness": {"table": [[5, 1e-3], [9, 1e-7]]},
                            "adaptive_dt": {"min": 0.001, "max": 0.02, "easy_iterations": 3, "hard_iterations": 5}}},
    "output": {"every_steps": 3, "plots": false, "checkpoint": {"every_steps": 7}}})";
}

TEST(Restart, ImplicitRunContinuesBitForBit) {
  const Spec spec = parse_spec(implicit_input_text());
  expect_restart_equals_uninterrupted("implicit", spec, [&](const fs::path& dir) {
    Spec first = spec;
    first.solver.max_steps = 12;
    return run_in(first, dir);
  });
  const fs::path tmp = fs::temp_directory_path();  // the directories scratch() made for "implicit"
  const Hdf5Reader whole(tmp / "matpoint_checkpoint_implicit_whole" / kCheckpointFile),
      parts(tmp / "matpoint_checkpoint_implicit_parts" / kCheckpointFile);
  for (const char* name : {"solver/acceleration", "solver/element", "solver/dt", "solver/history_marks"})
    EXPECT_TRUE(same(whole.doubles(name, whole.shape(name)), parts.doubles(name, parts.shape(name))))
        << name << " differs";
  auto totals = whole.doubles("solver/totals", {5}), parts_totals = parts.doubles("solver/totals", {5});
  totals.pop_back(), parts_totals.pop_back();  // steps, iterations, cuts, most iterations; not the seconds
  EXPECT_TRUE(same(totals, parts_totals)) << "the Newton totals differ";
}

// The Galerkin meshfree method (solver.basis "lme", Iaconeta 2017 §4.2): a block on a fixed floor,
// thrown down and sideways, vibrating. The nodes are Lagrangian and carry Newmark's history, so the
// checkpoint must keep their positions, velocities and accelerations (solver/meshfree_nodes), and
// the points' accelerations, from which the next step projects the nodes' history
// (solver/meshfree_point_accelerations); the particles carry the rest.
TEST(Restart, MeshfreeRunContinuesBitForBit) {
  const Spec spec = parse_spec(R"({"mesh": {"element": "q4", "min": [0, 0], "max": [1, 1], "cells": [4, 4]},
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 2e5, "nu": 0.3}],
    "bodies": [{"material": "m", "placement": "gauss", "shape": {"type": "box", "min": [0, 0], "max": [1, 0.5]},
                "velocity": [0.2, -1]}],
    "boundary_conditions": [{"type": "fixed", "boundary": "bottom"}],
    "loads": {"gravity": [0, -9.81]},
    "solver": {"type": "implicit_ul", "basis": "lme", "dt": 0.01, "end_time": 0.2,
               "implicit": {"initial_acceleration": "body_force"}},
    "output": {"every_steps": 3, "plots": false, "checkpoint": {"every_steps": 7},
               "node_probes": [{"name": "top", "position": [0.5, 0.5]}]}})");
  expect_restart_equals_uninterrupted("meshfree", spec, [&](const fs::path& dir) {
    Spec first = spec;
    first.solver.max_steps = 12;
    return run_in(first, dir);
  });
  const fs::path tmp = fs::temp_directory_path();
  const Hdf5Reader whole(tmp / "matpoint_checkpoint_meshfree_whole" / kCheckpointFile),
      parts(tmp / "matpoint_checkpoint_meshfree_parts" / kCheckpointFile);
  for (const char* name : {"solver/meshfree_nodes", "solver/meshfree_repairs", "solver/history_marks",
                           "solver/meshfree_point_accelerations"})
    EXPECT_TRUE(same(whole.doubles(name, whole.shape(name)), parts.doubles(name, parts.shape(name))))
        << name << " differs";
}

// A restart may change `output`: a probe added there has no values before the restart (nan in
// history.csv) and the followed particle's values after it.
TEST(Restart, ProbeAddedAtRestartStartsWithTheContinuedRun) {
  const Spec spec = parse_spec(input_text(2, "bspline2", R"("flip")"));
  const fs::path dir = scratch("probe_added");
  Spec first = spec;
  first.solver.max_steps = 23;
  ASSERT_EQ(run_in(first, dir).exit_code, 0);
  Spec probed = spec;
  probed.output.probes = {{"p", {0.5, 0.5, 0}}};
  probed.echo["output"]["probes"] = nlohmann::json::array({{{"name", "p"}, {"position", {0.5, 0.5}}}});
  const RunResult rest = run_in(probed, dir, dir / kCheckpointFile);
  ASSERT_EQ(rest.exit_code, 0) << rest.message;
  ASSERT_EQ(rest.history.probe_columns.size(), 10u);  // 2-D: x, u, v (2 each), 3 stresses, J
  std::size_t before = 0, after = 0;
  for (const auto& sample : rest.history.samples) {
    if (sample.step <= 23) before += sample.probes.empty() ? 1 : 0;
    if (sample.step > 23) after += sample.probes.size() == 10 ? 1 : 0;
  }
  EXPECT_GT(before, 0u);
  EXPECT_GT(after, 0u);
  EXPECT_EQ(before + after, rest.history.samples.size());
  EXPECT_NE(file_text(dir / "history.csv").find(",nan"), std::string::npos);
}

// --- refused checkpoints ---

struct Written {
  Spec spec;
  fs::path file;
};

Written written_checkpoint(const std::string& tag) {
  Spec spec = parse_spec(input_text(2, "linear", R"("flip")"));
  spec.solver.max_steps = 3;
  const fs::path dir = scratch(tag);
  EXPECT_EQ(run_in(spec, dir).exit_code, 0);
  return {spec, dir / kCheckpointFile};
}

std::string refusal(const Spec& spec, const fs::path& file) {
  try {
    Simulation<2> sim = build_simulation<2>(spec);
    RunCounters run;
    History history{2, 1, {}, {}, {}};
    read_checkpoint<2>(file, spec.echo, sim, run, history);
  } catch (const InputError& e) {
    EXPECT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].path, file.string());
    return e.what();
  }
  return "accepted";
}

TEST(Restart, TruncatedCheckpointIsRefused) {
  const auto [spec, file] = written_checkpoint("truncated");
  fs::resize_file(file, fs::file_size(file) / 2);
  EXPECT_NE(refusal(spec, file).find("not a usable checkpoint"), std::string::npos) << refusal(spec, file);
}

TEST(Restart, CheckpointWithDamagedDataIsRefused) {
  auto [spec, file] = written_checkpoint("damaged");
  // Overwrite one byte of the first particle's position, found by its bytes in the file.
  const double x0 = Hdf5Reader(file).doubles("particles/x", Hdf5Reader(file).shape("particles/x"))[0];
  std::string bytes = file_text(file);
  const auto at = bytes.find(std::string(reinterpret_cast<const char*>(&x0), sizeof x0));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 3] = static_cast<char>(bytes[at + 3] ^ 0x10);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  const std::string message = refusal(spec, file);
  EXPECT_NE(message.find("checksum"), std::string::npos) << message;
}

TEST(Restart, FilesThatAreNoCheckpointAreRefused) {
  const auto [spec, file] = written_checkpoint("not_checkpoint");
  std::ofstream(file, std::ios::trunc) << "{\"not\": \"hdf5\"}\n";
  EXPECT_NE(refusal(spec, file).find("not a readable HDF5 file"), std::string::npos);
  EXPECT_NE(refusal(spec, file.parent_path() / "missing.h5").find("no such file"), std::string::npos);
}

TEST(Restart, CheckpointOfOtherPhysicsIsRefusedButEndTimeMayChange) {
  const auto [spec, file] = written_checkpoint("other_input");
  Spec other = spec;
  other.echo["materials"][0]["E"] = 2e5;
  const std::string message = refusal(other, file);
  EXPECT_NE(message.find("materials[0].E"), std::string::npos) << message;
  Spec longer = spec;
  longer.echo["solver"]["end_time"] = 0.05;
  longer.echo["output"]["every_steps"] = 3;
  longer.echo["title"] = "continued";
  EXPECT_EQ(refusal(longer, file), "accepted");
}

TEST(Restart, CheckpointOfAnotherDimensionIsRefused) {
  const auto [spec, file] = written_checkpoint("dimension");
  const Spec one_d = parse_spec(input_text(1, "linear", R"("flip")"));
  try {
    Simulation<1> sim = build_simulation<1>(one_d);
    RunCounters run;
    History history{1, 1, {}, {}, {}};
    read_checkpoint<1>(file, one_d.echo, sim, run, history);
    FAIL() << "accepted a 2-D checkpoint for a 1-D input";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2-D run"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

TEST(CheckpointInput, ScheduleKeysAreReadAndChecked) {
  const std::string good = input_text(2, "linear", R"("flip")");
  const Spec spec = parse_spec(good);
  EXPECT_EQ(spec.output.checkpoint.every_steps, 7);
  EXPECT_EQ(spec.output.checkpoint.every_minutes, 0.0);
  const auto issues = [&](const std::string& checkpoint) {
    std::string text = good;
    text.replace(text.find(R"({"every_steps": 7})"), 18, checkpoint);
    try {
      (void)parse_spec(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(issues(R"({"every_minutes": 30})"), "accepted");
  EXPECT_NE(issues("{}").find("output.checkpoint: got {}, expected an object with every_steps"),
            std::string::npos)
      << issues("{}");
  EXPECT_NE(
      issues(R"({"every_minutes": 0})").find("output.checkpoint.every_minutes: got 0, expected a number > 0"),
      std::string::npos)
      << issues(R"({"every_minutes": 0})");
  EXPECT_NE(
      issues(R"({"every_steps": 0})").find("output.checkpoint.every_steps: got 0, expected an integer >= 1"),
      std::string::npos);
  EXPECT_NE(issues(R"({"each": 3})").find("output.checkpoint.each"), std::string::npos);
}

}  // namespace

namespace {

TEST(CheckpointSchedule, WallClockScheduleWritesAndKeepsThePreviousCheckpoint) {
  Spec spec = parse_spec(input_text(2, "linear", R"("flip")"));
  spec.output.checkpoint = {0, 1e-12};  // every_minutes: due after every step
  spec.solver.max_steps = 5;
  const fs::path dir = scratch("every_minutes");
  const RunResult result = run_in(spec, dir);
  ASSERT_EQ(result.exit_code, 0) << result.message;
  EXPECT_EQ(result.summary["checkpoint_step"], 5);
  EXPECT_EQ(Hdf5Reader(dir / kCheckpointFile).integer("simulation/step"), 5);
  EXPECT_EQ(Hdf5Reader(dir / kPreviousCheckpointFile).integer("simulation/step"), 4);
}

TEST(CheckpointSchedule, NoCheckpointWithoutScheduleOrInterrupt) {
  Spec spec = parse_spec(input_text(2, "linear", R"("flip")"));
  spec.output.checkpoint = {};
  spec.solver.max_steps = 3;
  const fs::path dir = scratch("unscheduled");
  const RunResult result = run_in(spec, dir);
  ASSERT_EQ(result.exit_code, 0) << result.message;
  EXPECT_FALSE(fs::exists(dir / kCheckpointFile));
  EXPECT_TRUE(result.summary["checkpoint"].is_null());
}

}  // namespace
