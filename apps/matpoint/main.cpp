// The matpoint command line: run, check, plot (DESIGN.md "Interfaces").
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli_suggestions.hpp"
#include "dispersion_command.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/core/parallel_session.hpp"
#include "matpoint/core/version.hpp"
#include "matpoint/explicit/setup_warnings.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/io/output_folder.hpp"
#include "matpoint/run/runner.hpp"
#include "run_estimate.hpp"
#include "scripts_location.hpp"
#include "stability_scan_command.hpp"
#include "verify_command.hpp"

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
    std::printf("estimate: %s\n", describe(estimate_run(spec)).c_str());
    return kExitOk;
  } catch (const InputError& error) {
    return report_input_error(error);
  }
}

int command_plot(const std::filesystem::path& dir, const std::filesystem::path& scripts_dir) {
  if (scripts_dir.empty()) {
    std::fprintf(stderr,
                 "error: the plotting scripts were not found (set MATPOINT_SCRIPTS_DIR, or install "
                 "matpoint with cmake --install)\n");
    return kExitOther;
  }
  if (const auto error = draw_plots(dir, scripts_dir); !error.empty()) {
    std::fprintf(stderr, "error: could not draw plots: %s\n", error.c_str());
    return kExitOther;
  }
  return kExitOk;
}

/// A path as a POSIX shell reads it back: quoted when it holds anything but plain characters.
std::string shell_word(const std::string& text) {
  const bool plain = !text.empty() && text.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789-_./,:=+@%") == std::string::npos;
  if (plain) return text;
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// A fresh run's folder must not hold another run's files: ParaView's file series and the plots
/// would mix two runs. With --overwrite those files (only matpoint's own) are deleted first.
bool prepare_output_folder(const std::filesystem::path& out, bool overwrite) {
  const auto files = run_files_in(out);
  if (files.empty()) return true;
  if (!overwrite) {
    std::fprintf(stderr,
                 "error: %s already holds the outputs of another run (%s); choose another --out, or add "
                 "--overwrite to delete those files first (other files in it are kept); nothing was run\n",
                 out.c_str(), describe_run_files(files).c_str());
    return false;
  }
  const std::size_t removed = remove_run_files(out);
  std::fprintf(stderr, "--overwrite: deleted %zu output file(s) of an earlier run from %s\n", removed,
               out.c_str());
  return true;
}

bool same_folder(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

/// An implicit run under MPI: every rank runs the whole simulation (only the linear solves are
/// shared), rank r > 0 writes into DIR.rank<r>, and the checkpoint it restarts from is the one in
/// its own folder. (An explicit run is decomposed: the ranks share one folder.)
void separate_rank_outputs(RunOptions& options) {
  const int rank = ParallelSession::rank();
  if (rank == 0) {
    if (ParallelSession::size() > 1)
      std::fprintf(stderr,
                   "note: an implicit run on %d MPI ranks: every rank runs the whole simulation (only "
                   "the linear solves with solver.implicit.linear_solver \"petsc\" are shared); rank r > 0 "
                   "writes into %s.rank<r>\n",
                   ParallelSession::size(), options.out_dir.string().c_str());
    return;
  }
  const std::string suffix = ".rank" + std::to_string(rank);
  if (!options.restart.empty())
    options.restart =
        std::filesystem::path(options.restart.parent_path().string() + suffix) / options.restart.filename();
  std::filesystem::path folder = options.out_dir.lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "out/" is "out"
  options.out_dir = std::filesystem::path(folder.string() + suffix);
  options.progress = false;
}

/// A decomposed run's rank r > 0: the run, and only its exit code (rank 0 reports). mpirun passes
/// SIGINT / SIGTERM to every rank: each finishes the step, and they checkpoint together.
int run_quietly(const Spec& spec, const RunOptions& options) {
  try {
    install_interrupt_handlers();
    return run_explicit(spec, options).exit_code;
  } catch (const InputError&) {
    return kExitBadInput;  // rank 0 reports it
  }
}

int command_run(const std::string& input, RunOptions options, bool overwrite) {
  Spec spec;
  try {
    spec = load_spec(input);
  } catch (const InputError& error) {
    return report_input_error(error);
  }
  // An explicit run on several ranks is decomposed (docs/scale-out.md): the ranks share the
  // output folder, which rank 0 prepares, and only rank 0 talks.
  const Communicator comm = Communicator::world();
  const bool decomposed = comm.distributed() && !spec.solver.is_implicit();
  if (!decomposed) separate_rank_outputs(options);
  const bool talks = comm.rank() == 0 || !decomposed;
  if (!talks) options.progress = false;
  // A restart continues in its checkpoint's folder; any other folder is checked like a fresh run's.
  const bool continues_in_place =
      !options.restart.empty() && same_folder(options.out_dir, options.restart.parent_path());
  bool prepared = continues_in_place || !talks || prepare_output_folder(options.out_dir, overwrite);
  if (decomposed) prepared = comm.max(prepared ? 0L : 1L) == 0;  // the others wait for rank 0's folder
  if (!prepared) return kExitBadInput;
  if (!talks) return run_quietly(spec, options);
  if (const auto warning = courant_warning(spec.solver); !warning.empty())
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  // The estimate before the wait: always when it is long, otherwise unless --quiet.
  if (const RunEstimate estimate = estimate_run(spec); options.progress || estimate.seconds > 600)
    std::fprintf(stderr, "estimate: %s\n", describe(estimate).c_str());
  for (const auto& warning : setup_warnings(spec)) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  try {
    install_interrupt_handlers();  // SIGINT / SIGTERM: finish the step, checkpoint, exit 128 + signal
    const RunResult result = run_explicit(spec, options);
    if (result.exit_code > 128) {
      const std::string checkpoint = result.summary.value("checkpoint", nlohmann::json()).is_string()
                                         ? result.summary["checkpoint"].get<std::string>()
                                         : (options.out_dir / kCheckpointFile).string();
      const std::string mpirun =
          decomposed ? "mpirun -n " + std::to_string(comm.size()) + " " : std::string();
      std::fprintf(stderr, "%s\nthe whole command: %smatpoint run %s --restart %s --out %s\n",
                   result.message.c_str(), mpirun.c_str(), shell_word(input).c_str(),
                   shell_word(checkpoint).c_str(), shell_word(options.out_dir.string()).c_str());
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

/// --threads: a whole number from 0 (all cores) to 4096, with a short message otherwise.
const CLI::Validator kThreadCount(
    [](std::string& text) -> std::string {
      int n = -1;
      std::size_t used = 0;
      try {
        n = std::stoi(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || n < 0 || n > 4096)
        return "got '" + text.substr(0, 40) + "', expected a whole number from 0 (all cores) to 4096";
      return "";
    },
    "INT in [0, 4096]");

/// OpenMP threads that wait at a barrier sleep instead of spinning (docs/user_guide.md "Threads"):
/// on a machine whose cores are busy with other work, spinning threads take the cores from the
/// ones with work, and a run on 2 threads became several times slower than on 1. libgomp reads
/// OMP_WAIT_POLICY once, when the program is loaded, before main: so when the user has not set
/// it, the program runs itself again with OMP_WAIT_POLICY=passive (a few milliseconds).
void use_passive_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;  // the user's choice, or already done
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: then run on with the default policy
}

namespace {

/// The words after `--`: PETSc's options (core/parallel_session.hpp); argc shrinks to the words before.
std::vector<std::string> split_petsc_options(int& argc, char** argv) {
  std::vector<std::string> petsc;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--") {
      petsc.assign(argv + i + 1, argv + argc);
      argc = i;
      break;
    }
  return petsc;
}

}  // namespace

int main(int argc, char** argv) {
  use_passive_wait_policy(argv);
  const std::vector<std::string> petsc_options = split_petsc_options(argc, argv);
  std::optional<ParallelSession> session;
  try {
    session.emplace(petsc_options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitBadInput;
  }
  CLI::App app{"matpoint: material point method simulations"};
  app.set_version_flag("--version", std::string("matpoint ") + kVersion);
  app.require_subcommand(1);
  app.footer(
      "'matpoint help COMMAND' shows a command's options; docs/user_guide.md is the guide.\n"
      "Exit codes: 0 ok, 1 other error, 2 bad input (nothing run), 3 numerical failure, 128 + signal "
      "when interrupted.\n");

  std::string input;
  RunOptions options;
  options.scripts_dir = find_scripts_dir();
  bool quiet = false;
  std::string out_dir = "out";
  auto* run = app.add_subcommand("run", "run a simulation described by an input file");
  run->add_option("input", input, "input file (JSON, comments allowed)")->required();
  auto* out_option =
      run->add_option("--out", out_dir,
                      "output folder (created if missing; with --restart: the checkpoint's folder)")
          ->capture_default_str();
  bool overwrite = false;
  run->add_flag("--overwrite", overwrite,
                "delete the outputs of an earlier run in --out first (otherwise such a folder is refused)");
  run->add_option("--threads", options.threads, "OpenMP threads (0: all cores)")->check(kThreadCount);
  run->add_flag("--quiet", quiet, "no progress output");
  std::string restart;
  run->add_option("--restart", restart, "continue from a checkpoint (e.g. OUT/checkpoint.h5) of this input");
  run->footer(
      "Example: matpoint run examples/two-disks/input.json --out two-disks\n"
      "Writes particles_*.vtu, results.pvd (ParaView), history.csv, summary.json and plots/*.png into "
      "--out; see docs/output.md.");

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

  if (const auto handled = handle_command_word(app, argc, argv)) return *handled;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError&) {
    std::fprintf(stderr, "%s\n", describe_extras(app).c_str());
    return kExitBadInput;
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (*dispersion.app) return dispersion.run();
    if (*check) return command_check(input);
    if (stability_scan.chosen()) return stability_scan.run();
    if (verify.chosen()) return verify.run();
    if (*plot) return command_plot(plot_dir, options.scripts_dir);
    options.out_dir = out_dir;
    options.progress = !quiet;
    options.restart = restart;
    if (!restart.empty() && out_option->count() == 0) {  // continue where the checkpoint is
      options.out_dir = options.restart.parent_path();
      if (options.out_dir.empty()) options.out_dir = ".";
    }
    return command_run(input, options, overwrite);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitOther;
  }
}
