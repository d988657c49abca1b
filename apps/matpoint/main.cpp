// The matpoint command line: run, check, plot (DESIGN.md "Interfaces").
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "dispersion_command.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/core/version.hpp"
#include "matpoint/explicit/setup_warnings.hpp"
#include "matpoint/explicit/runner.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "stability_scan_command.hpp"
#include "verify_command.hpp"

#ifndef MATPOINT_SCRIPTS_DIR
#define MATPOINT_SCRIPTS_DIR ""
#endif

namespace {

using namespace matpoint;

int report_input_error(const InputError& error) {
  for (const auto& issue : error.issues()) std::fprintf(stderr, "input error: %s\n", issue.message().c_str());
  std::fprintf(stderr, "%zu problem(s) found; nothing was run\n", error.issues().size());
  return kExitBadInput;
}

int command_check(const std::string& input) {
  try {
    const Spec spec = load_spec(input);
    check_setup(spec);  // what only the set-up finds: empty or overlapping bodies
    std::printf("%s: valid (%d-D, %zu material(s), %zu body(ies))\n", input.c_str(), spec.grid.dim,
                spec.materials.size(), spec.bodies.size());
    return kExitOk;
  } catch (const InputError& error) {
    return report_input_error(error);
  }
}

int command_run(const std::string& input, const RunOptions& options) {
  Spec spec;
  try {
    spec = load_spec(input);
  } catch (const InputError& error) {
    return report_input_error(error);
  }
  for (const auto& warning : setup_warnings(spec)) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  try {
    install_interrupt_handlers();  // SIGINT / SIGTERM: finish the step, checkpoint, exit 128 + signal
    const RunResult result = run_explicit(spec, options);
    if (result.exit_code > 128) {
      std::fprintf(stderr, "%s\n", result.message.c_str());
      return result.exit_code;
    }
    if (result.exit_code != kExitOk) {
      std::fprintf(stderr, "error: %s\nthe last good output and summary.json are in %s\n",
                   result.message.c_str(), options.out_dir.c_str());
      return result.exit_code;
    }
    const auto& s = result.summary;
    std::printf("%s: %ld steps, %zu particles, %.3g particle-steps/s; output in %s\n", input.c_str(),
                s["steps"].get<long>(), s["particles"].get<std::size_t>(),
                s["particle_steps_per_second"].get<double>(), options.out_dir.c_str());
    for (const auto& c : s["checks"])
      std::printf("  check %-40s %s  measured %s expected %g +/- %g\n", c["name"].get<std::string>().c_str(),
                  c["pass"].get<bool>() ? "PASS" : "FAIL", c["measured"].dump().c_str(),
                  c["expected"].get<double>(), c["tolerance"].get<double>());
    return kExitOk;
  } catch (const InputError& error) {
    return report_input_error(error);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"matpoint: material point method simulations"};
  app.set_version_flag("--version", std::string("matpoint ") + kVersion);
  app.require_subcommand(1);

  std::string input;
  RunOptions options;
  options.scripts_dir = MATPOINT_SCRIPTS_DIR;
  bool quiet = false;
  std::string out_dir = "out";
  auto* run = app.add_subcommand("run", "run a simulation described by an input file");
  run->add_option("input", input, "input file (JSON, comments allowed)")->required();
  run->add_option("--out", out_dir, "output folder (created if missing)")->capture_default_str();
  run->add_option("--threads", options.threads, "OpenMP threads (0: default)")->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet", quiet, "no progress output");
  std::string restart;
  run->add_option("--restart", restart, "continue from a checkpoint (e.g. OUT/checkpoint.h5) of this input");

  auto* check =
      app.add_subcommand("check", "validate an input file; exit 0, or print every problem and exit 2");
  check->add_option("input", input, "input file")->required();

  std::string plot_dir;
  auto* plot = app.add_subcommand("plot", "draw plots/*.png of an output folder");
  plot->add_option("dir", plot_dir, "output folder of a run")->required();
  const DispersionCommand dispersion = add_dispersion_command(app, options.scripts_dir);

  StabilityScanCommand stability_scan;
  stability_scan.add_to(app);

  VerifyCommand verify;
  verify.add_to(app, options.scripts_dir.string());

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (*dispersion.app) return dispersion.run();
    if (*check) return command_check(input);
    if (stability_scan.chosen()) return stability_scan.run();
    if (verify.chosen()) return verify.run();
    if (*plot) return draw_plots(plot_dir, options.scripts_dir) ? kExitOk : kExitOther;
    options.out_dir = out_dir;
    options.progress = !quiet;
    options.restart = restart;
    return command_run(input, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitOther;
  }
}
