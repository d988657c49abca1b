// summary.json of a run (docs/output.md): status, counts, throughput, solver statistics, the
// first and last energies and the input's checks. Built from plain facts, so it does not depend
// on the basis or the dimension of the run.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "matpoint/analysis/history.hpp"
#include "matpoint/explicit/fmpm.hpp"
#include "matpoint/explicit/mls_mapping.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/run/runner.hpp"

namespace matpoint {

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// What the time loop found out, in plain numbers.
struct RunFacts {
  std::string status;  // "ok", "interrupted" or "numerical_failure"
  int exit_code = 0;
  std::string message;
  long restart_step = -1;  // the step a restart began at; -1: not restarted
  std::filesystem::path checkpoint_file;
  long checkpoint_step = -1;  // -1: no checkpoint written or read
  int dimension = 0;
  std::size_t particles = 0;
  long nodes = 0;
  long steps = 0;
  double dt = 0.0, time = 0.0;
  int threads = 1;
  double wall = 0.0, step_wall = 0.0, step_cpu = 0.0;
  long outputs = 0;
  std::optional<FmpmStatistics> fmpm;             // FMPM and XPIC runs
  std::optional<MlsStatistics> mls;               // IMPM and MLS-velocity runs
  std::optional<std::size_t> logistic_fallbacks;  // logistic-regression contact normals
  std::optional<nlohmann::json> implicit;         // implicit runs: Newton, cuts, assembly/solve times
  std::optional<nlohmann::json> parallel;         // decomposed runs: ranks, threads, exchanges per step
  double momentum_scale = 0.0;                    // sum m |v| at time 0 (the momentum checks' scale)
  std::vector<double> final_stress_xx;            // every particle's sigma_xx (final-state measures)
  // The bodies' reach at the end: per axis the largest coordinate of a particle centre, and (3-D)
  // the largest distance of a particle centre from the z axis (final-state measures).
  std::array<double, 3> final_reach{kNoValue, kNoValue, kNoValue};
  double final_radius_xy = kNoValue;
  double final_runout_x = kNoValue;  // the x behind which 99 % of the mass lies
  struct Probe {
    long particle = -1;                      // the followed particle's id
    std::vector<double> reference_position;  // its X
  };
  std::vector<Probe> probes;          // output.probes, in input order
  std::vector<std::string> warnings;  // found while running (setup_warnings() adds the input's own)
};

/// The summary; `checks_pass` is true when every check of the input passed.
nlohmann::json run_summary(const Spec& spec, const RunOptions& options, const RunFacts& facts,
                           const History& history);

}  // namespace matpoint
