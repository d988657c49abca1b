// What a decomposed explicit run reports (issue 23; docs/scale-out.md §7-§8): every rank holds only
// its own particles, and the history row, the summary's facts, the energy guard and the output files
// must be those of the whole set. A Simulation<2> is built once; rank r keeps the particles with
// id % P == r (every other particle on 2 ranks) and owns a contiguous block of the nodes, and what
// each rank reports is compared with what the whole set gives on one rank (the serial code path).
// Expected: the same values to 1e-14 relative (sums in another order), exactly for maxima, minima,
// ids and copied values. Runs on 1 rank (the identity) and 2 (mpi.petsc_solver.ranks1 / ranks2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "matpoint/analysis/measures_eval.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/run/run_loop.hpp"

namespace {

using namespace matpoint;

const char* kInput = R"json({
  "grid": { "dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.05 },
  "materials": [ { "name": "elastic", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3 } ],
  "bodies": [
    { "name": "a", "material": "elastic", "shape": { "type": "disk", "center": [0.25, 0.25], "radius": 0.2 },
      "particles_per_cell": 2, "velocity": [0.1, 0.1] },
    { "name": "b", "material": "elastic", "shape": { "type": "disk", "center": [0.75, 0.75], "radius": 0.2 },
      "particles_per_cell": 2, "velocity": [-0.1, -0.1] } ],
  "solver": { "scheme": "musl", "transfer": "flip", "basis": "bspline2", "dt": 0.001, "end_time": 1.0,
              "max_energy_growth": 0.01 },
  "output": { "every_time": 0.05, "plots": false,
              "probes": [ { "name": "p", "position": [0.3, 0.2] }, { "name": "q", "position": [0.8, 0.7] } ] }
})json";

/// The whole particle set in a deformed, moving state (a smooth function of each particle's id),
/// with grid values on every node and accumulated totals: the same on every rank.
Simulation<2> whole_state() {
  const Spec spec = parse_spec(kInput);
  Simulation<2> sim = build_simulation<2>(spec);
  auto& ps = sim.particles;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const double s = static_cast<double>(ps.id[p]);
    ps.mass[p] *= 1 + 0.1 * std::sin(0.9 * s);  // unequal: no mass front falls exactly on a particle
    ps.v[p] += Vec<2>(0.01 * std::sin(s), 0.02 * std::cos(1.3 * s));
    ps.x[p] += Vec<2>(0.001 * std::cos(s), 0.002 * std::sin(0.7 * s));
    ps.F[p] << 1 + 0.01 * std::sin(2 * s), 0.003 * std::cos(s), 0.002 * std::sin(3 * s),
        1 - 0.02 * std::cos(s);
    ps.stress[p] << -100 * (1 + std::sin(0.1 * s)), 5 * std::cos(s), 5 * std::cos(s), 30 * std::sin(s);
  }
  for (std::size_t i = 0; i < sim.fields.mass.size(); ++i) {
    const double s = static_cast<double>(i);
    sim.fields.mass[i] = 1 + 0.5 * std::sin(0.3 * s);
    sim.fields.velocity_new[i] = Vec<2>(std::cos(0.2 * s), std::sin(0.5 * s));
  }
  sim.external_work = 0.75;
  sim.friction_work = 0.25;
  sim.external_impulse = Vec<2>(0.5, -1.5);
  sim.grid_momentum_difference = Vec<2>(1e-17, -2e-17);
  return sim;
}

/// This rank's part of `whole`: the particles with id % P == r, a block of the nodes, and 1/P of the
/// accumulated totals (exact for these values and P = 1, 2).
Simulation<2> rank_part(const Simulation<2>& whole, const Communicator& comm) {
  Simulation<2> sim = whole;
  sim.comm = comm;
  const auto P = static_cast<std::size_t>(comm.size()), r = static_cast<std::size_t>(comm.rank());
  std::vector<std::size_t> kept;
  for (std::size_t p = 0; p < whole.particles.size(); ++p)
    if (static_cast<std::size_t>(whole.particles.id[p]) % P == r) kept.push_back(p);
  for_each_array(sim.particles, [&](const char*, auto& array, std::size_t count) {
    auto copy = array;
    array.clear();
    for (std::size_t p : kept)
      array.insert(array.end(), copy.begin() + static_cast<std::ptrdiff_t>(p * count),
                   copy.begin() + static_cast<std::ptrdiff_t>((p + 1) * count));
  });
  const Index n = whole.grid.node_count;
  sim.owned_nodes = OwnedNodes::range(n * static_cast<Index>(r) / static_cast<Index>(P),
                                      n * static_cast<Index>(r + 1) / static_cast<Index>(P));
  sim.external_work /= static_cast<double>(P);
  sim.friction_work /= static_cast<double>(P);
  sim.external_impulse /= static_cast<double>(P);
  sim.grid_momentum_difference /= static_cast<double>(P);
  return sim;
}

/// Equal to 1e-14 relative; `scale`: of the terms summed, where they cancel (the total momentum).
void expect_close(double a, double b, const char* what, double scale = 0.0) {
  EXPECT_LE(std::abs(a - b), 1e-14 * std::max({std::abs(a), std::abs(b), scale}))
      << what << ": " << a << " vs " << b;
}
void expect_close(const std::array<double, 3>& a, const std::array<double, 3>& b, const char* what,
                  double scale = 0.0) {
  for (std::size_t k = 0; k < 3; ++k) expect_close(a[k], b[k], what, scale);
}

TEST(DistributedReports, HistoryRowEqualsTheWholeSets) {
  const Communicator comm = Communicator::world();
  const Spec spec = parse_spec(kInput);
  const Simulation<2> whole = whole_state();
  const Simulation<2> part = rank_part(whole, comm);
  const auto ids = probe_particle_ids<2>(whole.particles, spec.output.probes);
  EXPECT_EQ(probe_particle_ids<2>(part.particles, spec.output.probes, comm), ids);

  const HistorySample a = history_sample(whole, 2, ids), b = history_sample(part, 2, ids);
  expect_close(a.kinetic_energy, b.kinetic_energy, "kinetic energy");
  expect_close(a.strain_energy, b.strain_energy, "strain energy");
  expect_close(a.plastic_work, b.plastic_work, "plastic work");
  EXPECT_EQ(a.external_work, b.external_work);
  EXPECT_EQ(a.friction_work, b.friction_work);
  EXPECT_EQ(a.external_impulse, b.external_impulse);
  EXPECT_EQ(a.grid_momentum_difference, b.grid_momentum_difference);
  // the bodies' momenta nearly cancel: the scale of the round-off is theirs
  double body_scale = 0.0;
  for (const auto& m : a.body_momentum) body_scale = std::max({body_scale, std::abs(m[0]), std::abs(m[1])});
  expect_close(a.momentum, b.momentum, "momentum", body_scale);
  EXPECT_EQ(a.min_jacobian, b.min_jacobian);
  expect_close(a.rms_velocity_change, b.rms_velocity_change, "rms velocity change");
  for (int k = 0; k < 2; ++k) {
    expect_close(a.body_kinetic[k], b.body_kinetic[k], "body kinetic");
    expect_close(a.body_strain[k], b.body_strain[k], "body strain");
    expect_close(a.body_mass[k], b.body_mass[k], "body mass");
    expect_close(a.body_momentum[k], b.body_momentum[k], "body momentum");
    expect_close(a.body_com_velocity[k], b.body_com_velocity[k], "body com velocity");
    expect_close(a.body_com_position[k], b.body_com_position[k], "body com position");
  }
  expect_close(a.checkerboard_velocity, b.checkerboard_velocity, "checkerboard velocity");
  expect_close(a.grid_rms_velocity, b.grid_rms_velocity, "grid rms velocity");
  expect_close(a.hourglass_energy, b.hourglass_energy, "hourglass energy");
  EXPECT_EQ(a.probes, b.probes);  // copied from the rank that holds each particle
  ASSERT_EQ(a.probes.size(), 2u * 10u);

  const Diagnostics<2> d = measure_diagnostics(whole, 2), e = measure_diagnostics(part, 2);
  EXPECT_EQ(d.max_jacobian, e.max_jacobian);
}

TEST(DistributedReports, SummaryFactsEqualTheWholeSets) {
  const Communicator comm = Communicator::world();
  const Spec spec = parse_spec(kInput);
  const Simulation<2> whole = whole_state();
  const Simulation<2> part = rank_part(whole, comm);
  RunFacts a, b;
  run_loop_detail::add_state_facts(whole, a);
  run_loop_detail::add_state_facts(part, b);
  EXPECT_EQ(a.particles, whole.particles.size());
  EXPECT_EQ(b.particles, a.particles);
  EXPECT_EQ(b.final_reach[0], a.final_reach[0]);
  EXPECT_EQ(b.final_reach[1], a.final_reach[1]);
  EXPECT_TRUE(std::isnan(b.final_reach[2]));      // 2-D: none
  EXPECT_EQ(b.final_runout_x, a.final_runout_x);  // the same particle's x
  EXPECT_EQ(shock_plateau_stress(b.final_stress_xx), shock_plateau_stress(a.final_stress_xx));
  EXPECT_TRUE(std::isfinite(a.final_runout_x));
  // the mass front directly: all the mass lies behind the largest x and no smaller one; 37 % of it
  // behind the x where the particles sorted by x first reach 37 % of the mass
  double largest = -1.0, total = 0.0;
  std::vector<std::pair<double, double>> x_mass;
  for (std::size_t p = 0; p < whole.particles.size(); ++p) {
    largest = std::max(largest, whole.particles.x[p][0]);
    x_mass.emplace_back(whole.particles.x[p][0], whole.particles.mass[p]);
    total += whole.particles.mass[p];
  }
  EXPECT_EQ(run_loop_detail::mass_front_x(part.particles, 1.0, comm), largest);
  std::sort(x_mass.begin(), x_mass.end());
  double behind = 0.0, expected = 0.0;
  for (const auto& [x, m] : x_mass)
    if ((behind += m) >= 0.37 * total) {
      expected = x;
      break;
    }
  EXPECT_EQ(run_loop_detail::mass_front_x(part.particles, 0.37, comm), expected);
  const auto X = probe_reference_positions<2>(
      part.particles, probe_particle_ids<2>(whole.particles, spec.output.probes), comm);
  const auto Y = probe_reference_positions<2>(
      whole.particles, probe_particle_ids<2>(whole.particles, spec.output.probes), Communicator{});
  ASSERT_EQ(X.size(), 2u);
  EXPECT_EQ(X, Y);
}

TEST(DistributedReports, EnergyGuardDecidesAsOnTheWholeSet) {
  const Communicator comm = Communicator::world();
  const Spec spec = parse_spec(kInput);
  const Simulation<2> whole = whole_state();
  const Simulation<2> part = rank_part(whole, comm);
  // A start with half the present energy: the balance has grown, the guard stops both runs with
  // the same words (the growth, and the fastest particle of all ranks).
  History history{2, 2, {}, {}, {history_sample(whole, 2, {})}};
  history.samples[0].kinetic_energy *= 0.5;
  const auto message = [&](const Simulation<2>& sim) {
    EnergyGuard guard(spec.solver.max_energy_growth, history);
    try {
      guard.after_step(sim, true, [] { return OtherBodiesEnergy{}; });
    } catch (const NumericalFailure& failure) {
      return std::string(failure.what());
    }
    return std::string("no failure");
  };
  const std::string serial = message(whole);
  EXPECT_NE(serial.find("fastest"), std::string::npos) << serial;
  EXPECT_EQ(message(part), serial);
}

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Each rank writes its piece (the last one of several holds no particle), rank 0 the .pvtu naming
// them, results.pvd and history.csv.
TEST(DistributedReports, EachRankWritesItsPieceAndRankZeroTheIndex) {
  const Communicator comm = Communicator::world();
  Spec spec = parse_spec(kInput);
  spec.output.particles = true;
  Simulation<2> part = rank_part(whole_state(), comm);
  if (comm.size() > 1 && comm.rank() == comm.size() - 1)  // a rank without particles writes a piece too
    for_each_array(part.particles, [](const char*, auto& array, std::size_t) { array.clear(); });
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "matpoint_test_distributed_outputs";
  if (comm.rank() == 0) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  comm.barrier();
  {
    const auto ids = probe_particle_ids<2>(part.particles, spec.output.probes, comm);
    RunOutputs<2> outputs(spec, dir, History{2, 2, {}, run_loop_detail::probe_columns(spec), {}},
                          RunCounters{}, ids, comm);
    outputs.record(part, {});
    outputs.record(part, {});
    outputs.write_history();
  }
  comm.barrier();
  if (comm.size() == 1) {
    EXPECT_TRUE(std::filesystem::exists(dir / "particles_000001.vtu"));
    EXPECT_FALSE(std::filesystem::exists(dir / "particles_000001.pvtu"));
  } else {
    for (int r = 0; r < comm.size(); ++r) {
      char piece[64];
      std::snprintf(piece, sizeof piece, "particles_000001_r%04d.vtu", r);
      EXPECT_TRUE(std::filesystem::exists(dir / piece)) << piece;
      EXPECT_NE(read(dir / "particles_000001.pvtu").find(std::string("Source=\"") + piece + "\""),
                std::string::npos);
    }
    EXPECT_NE(read(dir / "results.pvd").find("file=\"particles_000001.pvtu\""), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir / "particles_000001.vtu"));
  }
  // history.csv: two rows plus the header, with the probes' columns
  const std::string csv = read(dir / "history.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_NE(csv.find("probe_q_J"), std::string::npos);
  comm.barrier();
  if (comm.rank() == 0 && std::getenv("MATPOINT_KEEP_TEST_OUTPUT") == nullptr)
    std::filesystem::remove_all(dir);
}

}  // namespace
