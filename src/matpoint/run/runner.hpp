// Runs a simulation from a validated Spec through the shared loop (run/run_loop.hpp) with the solver
// the input selects; the basis and dimension are chosen here, once, before any hot loop runs.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "matpoint/analysis/history.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

struct RunOptions {
  std::filesystem::path out_dir = "out";
  int threads = 0;                    // 0: OpenMP default
  bool progress = true;               // progress on stderr (a bar on a terminal, log lines otherwise)
  std::filesystem::path scripts_dir;  // folder of plot_history.py; empty: no plots
  std::filesystem::path restart;      // a checkpoint to continue from; empty: start at time 0
};

struct RunResult {
  int exit_code = 0;  // 0 ok, 3 numerical failure, 128 + signal number when interrupted
  std::string message;
  nlohmann::json summary;
  History history;  // one sample per output time
};

/// Throws InputError (before writing anything) when the spec cannot be set up, e.g. an empty body,
/// or when options.restart is not a usable checkpoint of this input.
RunResult run_explicit(const Spec& spec, const RunOptions& options);

/// Draws plots/*.png of an output folder with the project's matplotlib script (no shell involved);
/// returns "" on success, else why not (the script's own error message included).
std::string draw_plots(const std::filesystem::path& out_dir, const std::filesystem::path& scripts_dir);

}  // namespace matpoint
