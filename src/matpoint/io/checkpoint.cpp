#include "matpoint/io/checkpoint.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "matpoint/core/errors.hpp"
#include "matpoint/core/version.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/io/atomic_file.hpp"
#include "matpoint/io/hdf5_file.hpp"
#include "matpoint/parallel/box_partition.hpp"
#include "matpoint/particles/serial_order.hpp"

namespace matpoint {

namespace {

using Shape = std::vector<hsize_t>;
using json = nlohmann::json;

constexpr const char* kFormat = "matpoint checkpoint";
constexpr const char* kPieceFormat = "matpoint checkpoint piece";  // one rank's part (docs/scale-out.md §9)
// time, step, 3 energies, momentum[3], impulse[3], min J, rms dv, grid momentum difference[3],
// checkerboard velocity, grid rms velocity, hourglass energy
constexpr std::size_t kSampleColumns = 22;
constexpr std::size_t kBodyColumns =
    12;  // kinetic, strain, mass, momentum[3], centre-of-mass velocity[3], position[3]

hsize_t h(std::size_t n) { return static_cast<hsize_t>(n); }

// --- fixed-size Eigen vectors / matrices <-> flat row-major arrays ---

template <class M>
std::vector<double> flat(const std::vector<M>& in) {
  std::vector<double> out;
  out.reserve(in.size() * M::SizeAtCompileTime);
  for (const auto& m : in)
    for (int i = 0; i < M::RowsAtCompileTime; ++i)
      for (int j = 0; j < M::ColsAtCompileTime; ++j) out.push_back(m(i, j));
  return out;
}

template <class M>
void unflat(const std::vector<double>& in, std::vector<M>& out) {
  out.resize(in.size() / M::SizeAtCompileTime);
  std::size_t k = 0;
  for (auto& m : out)
    for (int i = 0; i < M::RowsAtCompileTime; ++i)
      for (int j = 0; j < M::ColsAtCompileTime; ++j) m(i, j) = in[k++];
}

template <class To, class From>
std::vector<To> convert(const std::vector<From>& in) {
  return std::vector<To>(in.begin(), in.end());
}

// --- X_p and V_p(0): kept by particle id in the file (simulation/initial_*), by storage index
// in the particle set. Ids are 0 .. n - 1 unless particles were deleted (a meshfree run's repair,
// particles/remove_particles.hpp): then the rows run to the largest id, and a deleted id's row is
// zero and never read. ---

template <int D>
std::vector<Vec<D>> by_id(const ParticleSet<D>& ps, const std::vector<Vec<D>>& values) {
  long rows = static_cast<long>(values.size());
  for (const long id : ps.id) rows = std::max(rows, id + 1);
  std::vector<Vec<D>> out(static_cast<std::size_t>(rows), Vec<D>::Zero());
  for (std::size_t p = 0; p < ps.size(); ++p) out.at(static_cast<std::size_t>(ps.id[p])) = values[p];
  return out;
}

template <int D>
void from_id(const ParticleSet<D>& ps, const std::vector<Vec<D>>& values, std::vector<Vec<D>>& out) {
  out.resize(ps.size());
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto id = static_cast<std::size_t>(ps.id[p]);
    if (ps.id[p] < 0 || id >= values.size())
      throw Hdf5Error("dataset particles/id holds " + std::to_string(ps.id[p]) + ", outside 0 .. n - 1");
    out[p] = values[id];
  }
}

// --- history rows ---

std::vector<double> history_rows(const History& history) {
  std::vector<double> out;
  for (const auto& s : history.samples) {
    const double row[kSampleColumns] = {s.time,
                                        static_cast<double>(s.step),
                                        s.kinetic_energy,
                                        s.strain_energy,
                                        s.external_work,
                                        s.momentum[0],
                                        s.momentum[1],
                                        s.momentum[2],
                                        s.external_impulse[0],
                                        s.external_impulse[1],
                                        s.external_impulse[2],
                                        s.min_jacobian,
                                        s.rms_velocity_change,
                                        s.grid_momentum_difference[0],
                                        s.grid_momentum_difference[1],
                                        s.grid_momentum_difference[2],
                                        s.checkerboard_velocity,
                                        s.grid_rms_velocity,
                                        s.hourglass_energy,
                                        s.friction_work,
                                        s.dt,
                                        s.plastic_work};
    out.insert(out.end(), row, row + kSampleColumns);
    for (int b = 0; b < history.body_count; ++b) {
      out.insert(out.end(), {s.body_kinetic[b], s.body_strain[b], s.body_mass[b]});
      out.insert(out.end(), s.body_momentum[b].begin(), s.body_momentum[b].end());
      out.insert(out.end(), s.body_com_velocity[b].begin(), s.body_com_velocity[b].end());
      out.insert(out.end(), s.body_com_position[b].begin(), s.body_com_position[b].end());
    }
  }
  return out;
}

std::vector<HistorySample> history_samples(const std::vector<double>& rows, std::size_t count, int bodies) {
  std::vector<HistorySample> out(count);
  const std::size_t width = kSampleColumns + kBodyColumns * static_cast<std::size_t>(bodies);
  for (std::size_t r = 0; r < count; ++r) {
    const double* x = rows.data() + r * width;
    HistorySample& s = out[r];
    s.time = x[0];
    s.step = static_cast<long>(x[1]);
    s.kinetic_energy = x[2], s.strain_energy = x[3], s.external_work = x[4];
    s.momentum = {x[5], x[6], x[7]};
    s.external_impulse = {x[8], x[9], x[10]};
    s.min_jacobian = x[11], s.rms_velocity_change = x[12];
    s.grid_momentum_difference = {x[13], x[14], x[15]};
    s.checkerboard_velocity = x[16], s.grid_rms_velocity = x[17], s.hourglass_energy = x[18];
    s.friction_work = x[19];
    s.dt = x[20];
    s.plastic_work = x[21];
    for (int b = 0; b < bodies; ++b) {
      const double* y = x + kSampleColumns + kBodyColumns * static_cast<std::size_t>(b);
      s.body_kinetic.push_back(y[0]);
      s.body_strain.push_back(y[1]);
      s.body_mass.push_back(y[2]);
      s.body_momentum.push_back({y[3], y[4], y[5]});
      s.body_com_velocity.push_back({y[6], y[7], y[8]});
      s.body_com_position.push_back({y[9], y[10], y[11]});
    }
  }
  return out;
}

// --- extra history columns: their names, '\n'-joined, and one row per sample ---

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += name + '\n';
  return out;
}

/// Named extra columns of the history (the probes' or the solver's): their names and one row per
/// sample, as datasets history/NAMES and history/ROWS.
using SampleColumns = std::vector<double> HistorySample::*;

struct ColumnGroup {
  std::string names_dataset, rows_dataset;
  const std::vector<std::string>& names;
  SampleColumns values;
};

ColumnGroup probe_group(const History& history) {
  return {"history/probe_columns", "history/probes", history.probe_columns, &HistorySample::probes};
}
ColumnGroup solver_group(const History& history) {
  return {"history/solver_columns", "history/solver", history.solver_columns, &HistorySample::solver};
}

void write_column_rows(Hdf5Writer& w, const History& history, const ColumnGroup& g) {
  const auto& [names_dataset, rows_dataset, names, values] = g;
  const std::size_t width = names.size();
  if (width == 0 || history.samples.empty()) return;
  std::vector<double> rows;
  for (const auto& s : history.samples) {
    std::vector<double> row = s.*values;
    row.resize(width, std::numeric_limits<double>::quiet_NaN());  // rows from before the columns
    rows.insert(rows.end(), row.begin(), row.end());
  }
  w.write(names_dataset, joined(names));
  w.write(rows_dataset, rows, {h(history.samples.size()), h(width)});
}

/// The column values of the samples when the checkpoint has the same columns as the input; a
/// restart that adds or changes probes (output may change) leaves the earlier rows without them.
void read_column_rows(const Hdf5Reader& r, History& history, const ColumnGroup& g) {
  const auto& [names_dataset, rows_dataset, names, values] = g;
  const std::size_t width = names.size();
  if (width == 0 || !r.has(names_dataset) || r.text(names_dataset) != joined(names)) return;
  const auto shape = r.shape(rows_dataset);
  if (shape.size() != 2 || shape[0] != history.samples.size() || shape[1] != width)
    throw Hdf5Error("dataset " + rows_dataset + " has the wrong shape");
  const auto rows = r.doubles(rows_dataset, shape);
  for (std::size_t k = 0; k < history.samples.size(); ++k)
    (history.samples[k].*values)
        .assign(rows.begin() + static_cast<std::ptrdiff_t>(k * width),
                rows.begin() + static_cast<std::ptrdiff_t>((k + 1) * width));
}

// --- the solver's own state: one dataset solver/NAME per array, their names '\n'-joined ---

void write_solver_state(Hdf5Writer& w, const RunCounters& run) {
  std::vector<std::string> names;
  for (const auto& [name, values] : run.solver_state) {
    w.write("solver/" + name, values, {h(values.size())});
    names.push_back(name);
  }
  w.write("solver/names", joined(names));
}

void read_solver_state(const Hdf5Reader& r, RunCounters& run) {
  run.solver_state.clear();
  if (!r.has("solver/names")) return;  // a checkpoint of a solver without state of its own
  std::istringstream names(r.text("solver/names"));
  for (std::string name; std::getline(names, name);) {
    const auto shape = r.shape("solver/" + name);
    if (shape.size() != 1) throw Hdf5Error("dataset solver/" + name + " is not a list");
    run.solver_state[name] = r.doubles("solver/" + name, shape);
  }
}

// --- .pvd entries: times and '\n'-joined names ---

void write_pvd(Hdf5Writer& w, const std::string& group, const PvdEntries& entries) {
  std::vector<double> times;
  std::string names;
  for (const auto& [t, name] : entries) {
    times.push_back(t);
    names += name + '\n';
  }
  w.write(group + "/times", times, {h(times.size())});
  w.write(group + "/files", names);
}

PvdEntries read_pvd(const Hdf5Reader& r, const std::string& group) {
  const auto count = r.shape(group + "/times");
  if (count.size() != 1) throw Hdf5Error("dataset " + group + "/times is not a list");
  const auto times = r.doubles(group + "/times", count);
  std::istringstream names(r.text(group + "/files"));
  PvdEntries out;
  for (double t : times) {
    std::string name;
    if (!std::getline(names, name)) throw Hdf5Error("dataset " + group + "/files has fewer names than times");
    out.emplace_back(t, name);
  }
  return out;
}

// --- the input check ---

/// "/bodies/0/velocity" -> "bodies[0].velocity"
std::string dotted(const std::string& pointer) {
  std::string out;
  std::istringstream parts(pointer);
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (part.empty()) continue;
    const bool index = part.find_first_not_of("0123456789") == std::string::npos;
    out += index ? "[" + part + "]" : (out.empty() ? "" : ".") + part;
  }
  return out.empty() ? "(root)" : out;
}

void check_same_physics(const std::filesystem::path& file, const json& written, const json& input) {
  if (physics_hash(written) == physics_hash(input)) return;
  std::string changed;
  int listed = 0;
  for (const auto& op : json::diff(physics_of(written), physics_of(input))) {
    if (listed++ == 5) {
      changed += ", ...";
      break;
    }
    changed += (changed.empty() ? "" : ", ") + dotted(op["path"].get<std::string>());
  }
  throw InputError({{file.string(), "a checkpoint of an input with other physics (changed: " + changed + ")",
                     "a checkpoint of this input; a restart may change only title, output, checks, "
                     "solver.end_time and solver.max_steps (docs/output.md)"}});
}

// --- the file's parts: the header, the particles, the simulation's and the run's counters, the
// history; a one-rank checkpoint has them all, a decomposed run's piece all but the history and its
// manifest all but the particles (docs/scale-out.md §9) ---

void write_header(Hdf5Writer& w, const std::string& format, int dimension, const json& input) {
  w.write("format", format);
  w.write("format_version", std::int64_t{kCheckpointFormatVersion});
  w.write("matpoint_version", std::string(kVersion));
  w.write("dimension", std::int64_t{dimension});
  w.write("input", input.dump());
  w.write("physics_hash", physics_hash(input));
}

template <int D>
void write_particles(Hdf5Writer& w, const ParticleSet<D>& ps) {
  const hsize_t n = h(ps.size());
  w.write("particles/x", flat(ps.x), {n, D});
  w.write("particles/v", flat(ps.v), {n, D});
  w.write("particles/mass", ps.mass, {n});
  w.write("particles/volume0", ps.volume0, {n});
  w.write("particles/size0", flat(ps.size0), {n, D});
  w.write("particles/F", flat(ps.F), {n, D, D});
  w.write("particles/stress", flat(ps.stress), {n, D, D});
  w.write("particles/stress_zz", ps.stress_zz, {h(ps.stress_zz.size())});  // plane strain only
  w.write("particles/L", flat(ps.L), {n, D, D});
  w.write("particles/material", convert<std::int32_t>(ps.material), {n});
  w.write("particles/body", convert<std::int32_t>(ps.body), {n});
  w.write("particles/id", convert<std::int64_t>(ps.id), {n});
  w.write("particles/state_stride", std::int64_t{ps.state_stride});
  w.write("particles/state", ps.state, {n, h(static_cast<std::size_t>(ps.state_stride))});
  w.write("particles/track_corners", std::int64_t{ps.track_corners ? 1 : 0});
  std::vector<double> corners;
  for (const auto& c : ps.corners)
    for (const auto& x : c) corners.insert(corners.end(), x.data(), x.data() + D);
  w.write("particles/corners", corners, {h(ps.corners.size()), ParticleSet<D>::kCorners, D});
  w.write("particles/temperature", ps.temperature, {h(ps.temperature.size())});  // coupled heat only
}

template <int D>
void write_simulation(Hdf5Writer& w, const Simulation<D>& sim) {
  w.write("simulation/time", sim.time);
  w.write("simulation/last_dt", sim.last_dt);
  w.write("simulation/step", std::int64_t{sim.step});
  w.write("simulation/external_work", sim.external_work);
  w.write("simulation/friction_work", sim.friction_work);
  w.write("simulation/boundary_heat", sim.boundary_heat);
  w.write("simulation/external_impulse",
          std::vector<double>(sim.external_impulse.data(), sim.external_impulse.data() + D), {D});
  w.write("simulation/grid_momentum_difference",
          std::vector<double>(sim.grid_momentum_difference.data(), sim.grid_momentum_difference.data() + D),
          {D});
}

void write_run(Hdf5Writer& w, const RunCounters& run) {
  w.write("run/dt", run.dt);
  w.write("run/momentum_scale", run.momentum_scale);
  w.write("run/total_mass", run.total_mass);
  w.write("run/outputs", std::int64_t{run.outputs});
  w.write("run/next_output_time", run.next_output_time);
  w.write("run/last_recorded_step", std::int64_t{run.last_recorded_step});
  w.write("run/next_fmpm_time", run.next_fmpm_time);
  w.write("run/fmpm_loops", std::int64_t{run.fmpm_loops});
  w.write("run/fmpm_passes", std::int64_t{run.fmpm_passes});
  w.write("run/fmpm_seconds", run.fmpm_seconds);
  w.write("run/step_wall", run.step_wall);
  w.write("run/step_cpu", run.step_cpu);
  w.write("run/wall", run.wall);
  w.write("run/threads", std::int64_t{run.threads});
  w.write("run/repartitions", std::int64_t{run.repartitions});
  w.write("run/partitioned_at", std::int64_t{run.partitioned_at});
  write_pvd(w, "run/results_pvd", run.results);
  write_pvd(w, "run/domains_pvd", run.domains);
  write_solver_state(w, run);
}

void write_history(Hdf5Writer& w, const History& history) {
  const std::size_t width = kSampleColumns + kBodyColumns * static_cast<std::size_t>(history.body_count);
  w.write("history/body_count", std::int64_t{history.body_count});
  w.write("history/samples", history_rows(history), {h(history.samples.size()), h(width)});
  write_column_rows(w, history, probe_group(history));
  write_column_rows(w, history, solver_group(history));
}

template <int D>
void write_contents(Hdf5Writer& w, const Simulation<D>& sim, const RunCounters& run, const History& history,
                    const json& input) {
  const auto& ps = sim.particles;
  write_header(w, kFormat, D, input);
  write_particles(w, ps);
  write_simulation(w, sim);
  const auto v0 = by_id(ps, ps.v0), x0 = by_id(ps, ps.x0);
  w.write("simulation/initial_velocity", flat(v0), {h(v0.size()), D});
  w.write("simulation/initial_position", flat(x0), {h(x0.size()), D});
  write_run(w, run);
  write_history(w, history);
}

/// Rank r's piece of a decomposed run's checkpoint: its particles in storage order (X_p and V_p(0)
/// too, in the same order), its own sums and counters, and its migration state.
template <int D>
void write_piece(Hdf5Writer& w, const Simulation<D>& sim, const RunCounters& run, const json& input) {
  const auto& ps = sim.particles;
  const hsize_t n = h(ps.size());
  write_header(w, kPieceFormat, D, input);
  write_particles(w, ps);
  w.write("particles/initial_velocity", flat(ps.v0), {n, D});
  w.write("particles/initial_position", flat(ps.x0), {n, D});
  write_simulation(w, sim);
  write_run(w, run);
  w.write("parallel/rank", std::int64_t{sim.comm.rank()});
  w.write("parallel/ranks", std::int64_t{sim.comm.size()});
  if (run.sort_keys.size() != ps.size())
    throw std::logic_error("checkpoint: " + std::to_string(run.sort_keys.size()) + " sort keys for " +
                           std::to_string(ps.size()) + " particles");
  w.write("parallel/sort_keys", run.sort_keys, {n});
  w.write("parallel/sorted_prefix", static_cast<std::int64_t>(run.sorted_prefix));
}

/// A decomposed run's manifest: the state every rank shares (rank 0's run counters), the history,
/// the rank count, the partition and the pieces' names by rank.
template <int D>
void write_manifest(Hdf5Writer& w, const Simulation<D>& sim, const RunCounters& run, const History& history,
                    const json& input) {
  write_header(w, kFormat, D, input);
  w.write("simulation/time", sim.time);
  w.write("simulation/last_dt", sim.last_dt);
  w.write("simulation/step", std::int64_t{sim.step});
  write_run(w, run);
  write_history(w, history);
  const int ranks = sim.comm.size();
  if (run.partition.size() != static_cast<std::size_t>(2 * D * ranks))
    throw std::logic_error("checkpoint: a partition of " + std::to_string(run.partition.size()) +
                           " entries for " + std::to_string(ranks) + " ranks");
  std::vector<std::string> pieces;
  for (int r = 0; r < ranks; ++r) pieces.push_back(checkpoint_piece_name(sim.step, r));
  w.write("parallel/ranks", std::int64_t{ranks});
  w.write("parallel/boxes", convert<std::int32_t>(run.partition),
          {h(static_cast<std::size_t>(ranks)), h(static_cast<std::size_t>(2 * D))});
  w.write("parallel/pieces", joined(pieces));
}

/// Returns the particle count.
template <int D>
hsize_t read_particles(const Hdf5Reader& r, ParticleSet<D>& ps, bool heat) {
  const auto xs = r.shape("particles/x");
  if (xs.size() != 2 || xs[1] != D) throw Hdf5Error("dataset particles/x is not an n x D array");
  const hsize_t n = xs[0];
  unflat(r.doubles("particles/x", {n, D}), ps.x);
  unflat(r.doubles("particles/v", {n, D}), ps.v);
  ps.mass = r.doubles("particles/mass", {n});
  ps.volume0 = r.doubles("particles/volume0", {n});
  unflat(r.doubles("particles/size0", {n, D}), ps.size0);
  unflat(r.doubles("particles/F", {n, D, D}), ps.F);
  unflat(r.doubles("particles/stress", {n, D, D}), ps.stress);
  ps.stress_zz = r.doubles("particles/stress_zz", {D == 2 ? n : 0});
  unflat(r.doubles("particles/L", {n, D, D}), ps.L);
  ps.material = convert<int>(r.int32s("particles/material", {n}));
  ps.body = convert<int>(r.int32s("particles/body", {n}));
  ps.id = convert<long>(r.int64s("particles/id", {n}));
  ps.state_stride = static_cast<int>(r.integer("particles/state_stride"));
  ps.state = r.doubles("particles/state", {n, h(static_cast<std::size_t>(ps.state_stride))});
  ps.track_corners = r.integer("particles/track_corners") != 0;
  const auto corners =
      r.doubles("particles/corners", {ps.track_corners ? n : 0, ParticleSet<D>::kCorners, D});
  ps.corners.resize(ps.track_corners ? n : 0);
  for (std::size_t p = 0; p < ps.corners.size(); ++p)
    for (int k = 0; k < ParticleSet<D>::kCorners; ++k)
      for (int a = 0; a < D; ++a) ps.corners[p][k][a] = corners[(p * ParticleSet<D>::kCorners + k) * D + a];
  ps.temperature = r.doubles("particles/temperature", {heat ? n : 0});
  return n;
}

template <int D>
void read_simulation(const Hdf5Reader& r, Simulation<D>& sim) {
  sim.time = r.number("simulation/time");
  sim.last_dt = r.number("simulation/last_dt");
  sim.step = r.integer("simulation/step");
  sim.external_work = r.number("simulation/external_work");
  sim.friction_work = r.number("simulation/friction_work");
  sim.boundary_heat = r.number("simulation/boundary_heat");
  const auto impulse = r.doubles("simulation/external_impulse", {D});
  for (int a = 0; a < D; ++a) sim.external_impulse[a] = impulse[a];
  const auto difference = r.doubles("simulation/grid_momentum_difference", {D});
  for (int a = 0; a < D; ++a) sim.grid_momentum_difference[a] = difference[a];
}

void read_run(const Hdf5Reader& r, RunCounters& run) {
  run.dt = r.number("run/dt");
  run.momentum_scale = r.number("run/momentum_scale");
  run.total_mass = r.number("run/total_mass");
  run.outputs = r.integer("run/outputs");
  run.next_output_time = r.number("run/next_output_time");
  run.last_recorded_step = r.integer("run/last_recorded_step");
  run.next_fmpm_time = r.number("run/next_fmpm_time");
  run.fmpm_loops = r.integer("run/fmpm_loops");
  run.fmpm_passes = r.integer("run/fmpm_passes");
  run.fmpm_seconds = r.number("run/fmpm_seconds");
  run.step_wall = r.number("run/step_wall");
  run.step_cpu = r.number("run/step_cpu");
  run.wall = r.number("run/wall");
  run.threads = static_cast<int>(r.integer("run/threads"));
  if (r.has("run/repartitions")) {  // written since 2026-12-08
    run.repartitions = r.integer("run/repartitions");
    run.partitioned_at = r.integer("run/partitioned_at");
  }
  run.results = read_pvd(r, "run/results_pvd");
  run.domains = read_pvd(r, "run/domains_pvd");
  read_solver_state(r, run);
}

void read_history(const Hdf5Reader& r, History& history) {
  const auto bodies = r.integer("history/body_count");
  if (bodies != history.body_count)
    throw Hdf5Error("history/body_count is " + std::to_string(bodies) + ", the input has " +
                    std::to_string(history.body_count) + " bodies");
  const auto rows = r.shape("history/samples");
  const std::size_t width = kSampleColumns + kBodyColumns * static_cast<std::size_t>(bodies);
  if (rows.size() != 2 || rows[1] != width) throw Hdf5Error("dataset history/samples has the wrong width");
  history.samples = history_samples(r.doubles("history/samples", rows), rows[0], history.body_count);
  read_column_rows(r, history, probe_group(history));
  read_column_rows(r, history, solver_group(history));
}

template <int D>
void read_contents(const Hdf5Reader& r, Simulation<D>& sim, RunCounters& run, History& history) {
  auto& ps = sim.particles;
  const hsize_t n = read_particles(r, sim.particles, sim.heat.enabled);
  read_simulation(r, sim);
  // n rows, or more when particles were deleted (by_id); from_id checks every id against them
  const auto rows = r.shape("simulation/initial_velocity");
  const hsize_t by_id_rows = rows.size() == 2 && rows[0] >= n ? rows[0] : n;
  std::vector<Vec<D>> by_id_values;
  unflat(r.doubles("simulation/initial_velocity", {by_id_rows, D}), by_id_values);
  from_id(ps, by_id_values, ps.v0);
  unflat(r.doubles("simulation/initial_position", {by_id_rows, D}), by_id_values);
  from_id(ps, by_id_values, ps.x0);
  read_run(r, run);
  read_history(r, history);
}

InputError damaged(const std::filesystem::path& file, const std::string& what) {
  return InputError({{file.string(), "a file that is not a usable checkpoint: " + what,
                      "a complete matpoint checkpoint (written as " + std::string(kCheckpointFile) +
                          ", with the one before it kept as " + kPreviousCheckpointFile + ")"}});
}

/// Format, version, dimension and physics of a checkpoint or piece: Hdf5Error (damaged) or
/// InputError (other physics).
void check_header(const Hdf5Reader& r, const std::filesystem::path& file, const std::string& format, int D,
                  const json& input) {
  if (!r.has("format")) throw Hdf5Error("it is not a matpoint checkpoint");
  const std::string found = r.text("format");
  if (found == kPieceFormat && format != kPieceFormat)
    throw Hdf5Error("it is one rank's piece of a decomposed run's checkpoint; restart from the " +
                    std::string(kCheckpointFile) + " that names it");
  if (found != format) throw Hdf5Error("it is not a " + format);
  const auto version = r.integer("format_version");
  if (version != kCheckpointFormatVersion)
    throw Hdf5Error("format version " + std::to_string(version) + ", this matpoint reads version " +
                    std::to_string(kCheckpointFormatVersion));
  const auto dim = r.integer("dimension");
  if (dim != D)
    throw Hdf5Error("a " + std::to_string(dim) + "-D run, the input is " + std::to_string(D) + "-D");
  json written;
  try {
    written = json::parse(r.text("input"));
  } catch (const json::exception&) {
    throw Hdf5Error("dataset input is not JSON");
  }
  check_same_physics(file, written, input);  // InputError: passes through
}

std::filesystem::path folder_of(const std::filesystem::path& file) {
  return file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
}

/// Renames the complete, fsynced `partial` onto `file`, the present `file` becoming `previous` (a
/// second name for the same file first, so that `file` never goes missing).
void replace_keeping_previous(const std::filesystem::path& partial, const std::filesystem::path& file,
                              const std::filesystem::path& previous) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    const std::filesystem::path link = previous.string() + ".partial";
    std::filesystem::remove(link, ec);
    std::filesystem::create_hard_link(file, link, ec);
    if (ec) std::filesystem::copy_file(file, link, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::rename(link, previous);
  }
  std::filesystem::rename(partial, file);
  sync_to_disk(folder_of(file));
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The end of one part of a collective write or read: when a rank failed, every rank throws the
/// error of the lowest failing rank (`error`: this rank's, empty when it succeeded).
struct Settled {
  int rank = -1;  // the lowest failing rank; -1: none failed
  std::string error;
};
Settled settle(const Communicator& comm, const std::string& error) {
  constexpr long kNone = std::numeric_limits<long>::max();
  const long first = comm.min(error.empty() ? kNone : static_cast<long>(comm.rank()));
  if (first == kNone) return {};
  return {static_cast<int>(first), comm.broadcast(error, static_cast<int>(first))};
}

void settle_write(const Communicator& comm, const std::string& error, const std::string& what) {
  if (const Settled s = settle(comm, error); s.rank >= 0)
    throw std::runtime_error("rank " + std::to_string(s.rank) + " could not write " + what + ": " + s.error);
}

/// After a new manifest: deletes the pieces (and .partial leftovers of killed runs) of steps
/// before `step` that neither `file` nor `previous` names. Later steps' pieces are left alone
/// (another rank may be writing its next one already). Never throws.
void remove_unnamed_pieces(const std::filesystem::path& file, const std::filesystem::path& previous,
                           long step) {
  std::set<std::string> named;
  for (const auto& manifest : {file, previous}) {
    try {
      const Hdf5Reader r(manifest);
      if (r.has("parallel/pieces"))
        for (auto& name : lines_of(r.text("parallel/pieces"))) named.insert(std::move(name));
    } catch (const std::exception&) {
      // a missing or damaged manifest names nothing
    }
  }
  static const std::regex piece(R"(checkpoint\.s(\d+)\.r\d+\.h5(\.partial)?)");
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder_of(file), ec)) {
    const std::string name = entry.path().filename().string();
    std::smatch m;
    if (!std::regex_match(name, m, piece) || named.contains(name) || std::stol(m[1].str()) >= step) continue;
    std::filesystem::remove(entry.path(), ec);
  }
}

/// The ranks' boxes of bricks in a decomposed run's manifest (BoxPartition::ints), checked to be a
/// partition of the grid's bricks. A manifest written before the boxes (up to 2026-12-07) holds
/// the slab cut along the last axis (`parallel/partition`: rank r's first brick layer, then the
/// layer count), read as the boxes of those slabs.
template <int D>
std::vector<int> read_boxes(const Hdf5Reader& manifest, const Grid<D>& grid, int ranks) {
  const auto P = static_cast<std::size_t>(ranks);
  std::vector<int> boxes;
  if (manifest.has("parallel/boxes")) {
    boxes = convert<int>(manifest.int32s("parallel/boxes", {h(P), h(2 * D)}));
  } else {
    const auto first = convert<int>(manifest.int32s("parallel/partition", {h(P + 1)}));
    const int layers = BrickSchedule<D>::bricks_along(grid, D - 1);
    if (first.front() != 0 || first.back() != layers || !std::is_sorted(first.begin(), first.end()))
      throw Hdf5Error("dataset parallel/partition is not a cut of the grid's " + std::to_string(layers) +
                      " brick layers");
    for (std::size_t r = 0; r < P; ++r) {
      std::array<int, 2 * D> box{};  // begin per axis, then end per axis
      for (int a = 0; a < D; ++a) box[D + a] = BrickSchedule<D>::bricks_along(grid, a);
      box[D - 1] = first[r], box[2 * D - 1] = first[r + 1];
      if (first[r] == first[r + 1]) box.fill(0);  // a rank without cells
      boxes.insert(boxes.end(), box.begin(), box.end());
    }
  }
  try {
    return BoxPartition<D>::from_ints(grid, boxes).ints();
  } catch (const std::invalid_argument& e) {
    throw Hdf5Error(std::string("dataset parallel/boxes is not a partition of the grid's bricks: ") +
                    e.what());
  }
}

/// Rank r's part of a decomposed run's checkpoint: its piece, named by the manifest `r`.
template <int D>
void read_piece(const Hdf5Reader& manifest, const std::filesystem::path& file, const json& input,
                Simulation<D>& sim, RunCounters& run) {
  const int ranks = sim.comm.size(), rank = sim.comm.rank();
  const auto pieces = lines_of(manifest.text("parallel/pieces"));
  if (pieces.size() != static_cast<std::size_t>(ranks))
    throw Hdf5Error("dataset parallel/pieces names " + std::to_string(pieces.size()) + " pieces for " +
                    std::to_string(ranks) + " ranks");
  auto partition = read_boxes<D>(manifest, sim.grid, ranks);
  const long step = manifest.integer("simulation/step");
  const std::filesystem::path file_of_piece = folder_of(file) / pieces[static_cast<std::size_t>(rank)];
  try {
    const Hdf5Reader r(file_of_piece);
    check_header(r, file_of_piece, kPieceFormat, D, input);
    if (r.integer("parallel/rank") != rank || r.integer("parallel/ranks") != ranks)
      throw Hdf5Error("the piece of another rank or rank count");
    if (r.integer("simulation/step") != step)
      throw Hdf5Error("a piece of step " + std::to_string(r.integer("simulation/step")) +
                      ", the manifest's is " + std::to_string(step));
    auto& ps = sim.particles;
    const hsize_t n = read_particles(r, sim.particles, sim.heat.enabled);
    unflat(r.doubles("particles/initial_velocity", {n, D}), ps.v0);
    unflat(r.doubles("particles/initial_position", {n, D}), ps.x0);
    read_simulation(r, sim);
    read_run(r, run);  // this rank's counters (total mass, timings, FMPM statistics)
    run.sort_keys = r.int64s("parallel/sort_keys", {n});
    const auto prefix = r.integer("parallel/sorted_prefix");
    if (prefix < 0 || static_cast<hsize_t>(prefix) > n)
      throw Hdf5Error("dataset parallel/sorted_prefix is out of range");
    run.sorted_prefix = static_cast<std::size_t>(prefix);
    run.partition = std::move(partition);
  } catch (const Hdf5Error& e) {
    throw damaged(file_of_piece, e.what());
  }
}

/// Appends the particles `which` of `from` to `to` (every array of for_each_array; both sets
/// have the same arrays in use).
template <int D>
void append_particles(ParticleSet<D>& to, const ParticleSet<D>& from, const std::vector<std::size_t>& which) {
  int k = 0;
  for_each_array(to, [&](const char*, auto& out, std::size_t count) {
    int j = 0;
    for_each_array(from, [&](const char*, const auto& in, std::size_t) {
      if (j++ != k) return;
      if constexpr (std::is_same_v<std::remove_cvref_t<decltype(in)>, std::remove_cvref_t<decltype(out)>>)
        for (const std::size_t p : which)
          out.insert(out.end(), in.begin() + static_cast<std::ptrdiff_t>(p * count),
                     in.begin() + static_cast<std::ptrdiff_t>((p + 1) * count));
    });
    ++k;
  });
}

/// A checkpoint of `written` ranks read on this run's other number of ranks (docs/scale-out.md §9):
/// every rank reads every piece (a one-rank checkpoint: the whole file), the boxes are
/// balanced anew over the checkpoint's particles, and each rank keeps the particles of its cells
/// in (sort key, id) order, which is the order in which every run, on any rank count, visits a
/// brick's particles (BrickSchedule::order_arrivals); so the particles continue bit for bit, and
/// the sums over particles (history) differ in round-off as between any two rank counts. The
/// sums each rank accumulates (external work, impulse, friction work) go to rank 0; the run
/// counters are the manifest's.
template <int D>
void read_redistributed(const Hdf5Reader& manifest, const std::filesystem::path& file, const json& input,
                        long written, Simulation<D>& sim, RunCounters& run) {
  const bool heat = sim.heat.enabled;
  ParticleSet<D> all;
  all.has_temperature = heat;
  std::vector<Index> keys;
  double external_work = 0.0, friction_work = 0.0, boundary_heat = 0.0;
  Vec<D> impulse = Vec<D>::Zero();
  const auto add_sums = [&](const Hdf5Reader& r) {  // a rank's (or the one rank's) own sums
    external_work += r.number("simulation/external_work");
    friction_work += r.number("simulation/friction_work");
    boundary_heat += r.number("simulation/boundary_heat");
    const auto rank_impulse = r.doubles("simulation/external_impulse", {D});
    for (int a = 0; a < D; ++a) impulse[a] += rank_impulse[a];
  };
  if (written == 1) {  // the serial storage order is the (key, id) order: key = the storage index
    const hsize_t n = read_particles(manifest, all, heat);
    std::vector<Vec<D>> by_id_values;
    unflat(manifest.doubles("simulation/initial_velocity", {n, D}), by_id_values);
    from_id(all, by_id_values, all.v0);
    unflat(manifest.doubles("simulation/initial_position", {n, D}), by_id_values);
    from_id(all, by_id_values, all.x0);
    add_sums(manifest);
    for (std::size_t p = 0; p < n; ++p) keys.push_back(static_cast<Index>(p));
  } else {
    const auto pieces = lines_of(manifest.text("parallel/pieces"));
    if (pieces.size() != static_cast<std::size_t>(written))
      throw Hdf5Error("dataset parallel/pieces names " + std::to_string(pieces.size()) + " pieces for " +
                      std::to_string(written) + " ranks");
    const long step = manifest.integer("simulation/step");
    for (long k = 0; k < written; ++k) {
      const std::filesystem::path file_of_piece = folder_of(file) / pieces[static_cast<std::size_t>(k)];
      try {
        const Hdf5Reader r(file_of_piece);
        check_header(r, file_of_piece, kPieceFormat, D, input);
        if (r.integer("parallel/rank") != k || r.integer("parallel/ranks") != written)
          throw Hdf5Error("the piece of another rank or rank count");
        if (r.integer("simulation/step") != step)
          throw Hdf5Error("a piece of another step than the manifest's");
        ParticleSet<D> part;
        part.has_temperature = heat;
        const hsize_t n = read_particles(r, part, heat);
        unflat(r.doubles("particles/initial_velocity", {n, D}), part.v0);
        unflat(r.doubles("particles/initial_position", {n, D}), part.x0);
        const auto part_keys = r.int64s("parallel/sort_keys", {n});
        keys.insert(keys.end(), part_keys.begin(), part_keys.end());
        add_sums(r);
        if (k == 0) all.state_stride = part.state_stride, all.track_corners = part.track_corners;
        std::vector<std::size_t> every(n);
        for (std::size_t p = 0; p < every.size(); ++p) every[p] = p;
        append_particles(all, part, every);
      } catch (const Hdf5Error& e) {
        throw damaged(file_of_piece, e.what());
      }
    }
  }
  // The partition of the present particles, and this rank's of them in (key, id) order.
  std::vector<std::array<int, D>> cells(all.size());
  for (std::size_t p = 0; p < all.size(); ++p) cells[p] = sim.grid.cell_coords(all.x[p]);
  const auto partition = BoxPartition<D>::balanced(sim.grid, cells, sim.comm.size());
  std::vector<std::size_t> mine;
  for (std::size_t p = 0; p < all.size(); ++p)
    if (partition.owner_of_cell(cells[p]) == sim.comm.rank()) mine.push_back(p);
  std::sort(mine.begin(), mine.end(), [&](std::size_t a, std::size_t b) {
    return serially_before(keys[a], all.id[a], keys[b], all.id[b]);
  });
  auto& ps = sim.particles;
  ps.state_stride = all.state_stride, ps.track_corners = all.track_corners;
  for_each_array(ps, [](const char*, auto& array, std::size_t) { array.clear(); });
  append_particles(ps, all, mine);
  run.partition = partition.ints();
  run.sort_keys.clear();
  for (const std::size_t p : mine) run.sort_keys.push_back(keys[p]);
  run.sorted_prefix = mine.size();
  run.total_mass = 0.0;  // this rank's, as the stepper sums it at the start (gravity's impulse)
  for (std::size_t p = 0; p < ps.size(); ++p)
    if (sim.rigid_material.empty() || !sim.rigid_material[ps.material[p]]) run.total_mass += ps.mass[p];
  const bool first = sim.comm.rank() == 0;
  sim.external_work = first ? external_work : 0.0, sim.friction_work = first ? friction_work : 0.0;
  sim.boundary_heat = first ? boundary_heat : 0.0;
  sim.external_impulse = first ? impulse : Vec<D>::Zero();
  sim.grid_momentum_difference.setZero();  // recomputed by the next scatter
}

/// This rank's whole read: the checkpoint of a one-rank run, or the manifest and this rank's piece.
template <int D>
void read_on_this_rank(const std::filesystem::path& file, const json& input, Simulation<D>& sim,
                       RunCounters& run, History& history) {
  try {
    const Hdf5Reader r(file);
    check_header(r, file, kFormat, D, input);
    const long ranks = r.has("parallel/ranks") ? r.integer("parallel/ranks") : 1;
    if (ranks != sim.comm.size()) {  // written on another rank count: redistributed
      read_history(r, history);
      read_run(r, run);
      read_redistributed<D>(r, file, input, ranks, sim, run);
      sim.time = r.number("simulation/time");
      sim.last_dt = r.number("simulation/last_dt");
      sim.step = r.integer("simulation/step");
      run.partitioned_at = sim.step;  // the partition was made at this step
      return;
    }
    if (ranks == 1) {
      read_contents<D>(r, sim, run, history);
      return;
    }
    read_history(r, history);
    read_piece<D>(r, file, input, sim, run);  // InputError: names the piece
    sim.time = r.number("simulation/time");   // the manifest's (equal to the piece's)
    sim.last_dt = r.number("simulation/last_dt");
  } catch (const Hdf5Error& e) {
    throw damaged(file, e.what());
  }
}

}  // namespace

std::string checkpoint_piece_name(long step, int rank) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint.s%08ld.r%04d.h5", step, rank);
  return name;
}

json physics_of(const json& input) {
  json physics = input;
  if (!physics.is_object()) return physics;
  for (const char* key : {"title", "output", "checks"}) physics.erase(key);
  if (const auto solver = physics.find("solver"); solver != physics.end() && solver->is_object()) {
    solver->erase("end_time");
    solver->erase("max_steps");
  }
  return physics;
}

std::string physics_hash(const json& input) {
  const std::string text = physics_of(input).dump();
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << fnv1a64(text.data(), text.size());
  return out.str();
}

template <int D>
void write_checkpoint(const std::filesystem::path& file, const std::filesystem::path& previous,
                      const Simulation<D>& sim, const RunCounters& run, const History& history,
                      const json& input) {
  const std::filesystem::path partial = file.string() + ".partial";
  const Communicator& comm = sim.comm;
  if (!comm.distributed()) {
    {
      Hdf5Writer w(partial);
      write_contents<D>(w, sim, run, history, input);
      w.close();
    }
    sync_to_disk(partial);
    replace_keeping_previous(partial, file, previous);
    return;
  }
  // Every piece is complete on the disk before the manifest names it; until the new manifest
  // takes the name `file`, the one it replaces and its pieces stay untouched.
  std::string error;
  try {
    const std::filesystem::path piece = folder_of(file) / checkpoint_piece_name(sim.step, comm.rank());
    const std::filesystem::path piece_partial = piece.string() + ".partial";
    {
      Hdf5Writer w(piece_partial);
      write_piece<D>(w, sim, run, input);
      w.close();
    }
    sync_to_disk(piece_partial);
    std::filesystem::rename(piece_partial, piece);
    sync_to_disk(folder_of(file));
  } catch (const std::exception& e) {
    error = e.what();
  }
  settle_write(comm, error, "its checkpoint piece");
  if (comm.rank() == 0) {
    try {
      {
        Hdf5Writer w(partial);
        write_manifest<D>(w, sim, run, history, input);
        w.close();
      }
      sync_to_disk(partial);
      replace_keeping_previous(partial, file, previous);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  settle_write(comm, error, "the checkpoint manifest " + file.string());
  if (comm.rank() == 0) remove_unnamed_pieces(file, previous, sim.step);
}

template <int D>
void read_checkpoint(const std::filesystem::path& file, const json& input, Simulation<D>& sim,
                     RunCounters& run, History& history) {
  if (!sim.comm.distributed()) {
    read_on_this_rank<D>(file, input, sim, run, history);
    return;
  }
  // Every rank reads; when any failed, every rank throws the lowest failing rank's error (a rank
  // whose piece is damaged must not leave the others waiting in the run's first collective).
  std::vector<InputIssue> issues;
  try {
    read_on_this_rank<D>(file, input, sim, run, history);
  } catch (const InputError& e) {
    issues = e.issues();
  } catch (const std::exception& e) {
    issues = damaged(file, e.what()).issues();
  }
  std::string mine;
  for (const auto& issue : issues) mine += issue.path + '\n' + issue.value + '\n' + issue.expected + '\n';
  const Settled settled = settle(sim.comm, mine);
  if (settled.rank < 0) return;
  const auto lines = lines_of(settled.error);
  std::vector<InputIssue> agreed;
  for (std::size_t k = 0; k + 2 < lines.size(); k += 3)
    agreed.push_back({lines[k], lines[k + 1], lines[k + 2]});
  throw InputError(std::move(agreed));
}

#define MATPOINT_INSTANTIATE(D)                                                                             \
  template void write_checkpoint<D>(const std::filesystem::path&, const std::filesystem::path&,             \
                                    const Simulation<D>&, const RunCounters&, const History&, const json&); \
  template void read_checkpoint<D>(const std::filesystem::path&, const json&, Simulation<D>&, RunCounters&, \
                                   History&);
MATPOINT_INSTANTIATE(1)
MATPOINT_INSTANTIATE(2)
MATPOINT_INSTANTIATE(3)
#undef MATPOINT_INSTANTIATE

}  // namespace matpoint
