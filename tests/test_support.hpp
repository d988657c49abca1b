// Helpers shared by the tests: load an example's input and run it quietly in a scratch folder.
#pragma once

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "matpoint/analysis/verification.hpp"
#include "matpoint/run/runner.hpp"
#include "matpoint/io/input.hpp"

namespace matpoint::test {

inline Spec load_example(const std::string& name, const std::string& file = "input.json") {
  return load_spec(std::filesystem::path(MATPOINT_EXAMPLES_DIR) / name / file);
}

/// A scratch folder of this test process: /tmp/matpoint_test_<pid>_<tag>. The process id keeps
/// test runs of several checkouts on one machine (or ctest -j) out of each other's files.
inline std::filesystem::path scratch_folder(const std::string& tag) {
  return std::filesystem::temp_directory_path() / ("matpoint_test_" + std::to_string(::getpid()) + "_" + tag);
}

/// Runs without particle files, plots or progress; returns the run's result (history included).
inline RunResult run_quietly(Spec spec, const std::string& tag) {
  spec.output.particles = false;
  spec.output.plots = false;
  RunOptions options;
  options.out_dir = scratch_folder(tag);
  options.progress = false;
  options.threads = 1;  // ctest runs tests side by side: one thread each avoids oversubscription
  RunResult result = run_explicit(spec, options);
  std::error_code ignored;
  std::filesystem::remove_all(options.out_dir, ignored);  // the result holds all a test reads
  return result;
}

/// The measured value of the run's check on `measure` (the input must declare such a check).
inline double measured(const RunResult& result, const std::string& measure) {
  for (const auto& check : result.summary["checks"])
    if (check["measure"] == measure && check["measured"].is_number()) return check["measured"].get<double>();
  return std::nan("");
}

/// Least-squares slope of log(error) against log(h): the observed order of convergence.
inline double observed_order(const std::vector<double>& h, const std::vector<double>& error) {
  return least_squares_order(h, error);
}

}  // namespace matpoint::test
