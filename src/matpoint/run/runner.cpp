#include "matpoint/run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "matpoint/analysis/probes.hpp"
#include "matpoint/core/subprocess.hpp"
#include "matpoint/run/run_by_solver.hpp"
#include "matpoint/run/run_loop.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

namespace run_loop_detail {

int current_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

std::vector<std::string> probe_columns(const Spec& spec) {
  std::vector<std::string> out;
  for (const auto& probe : spec.output.probes) {
    const auto names = probe_column_names(probe.name, spec.grid.dim);
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

}  // namespace run_loop_detail

namespace {

template <int D>
RunResult run_implicit_dim(const Spec& spec, const RunOptions& options) {
  mesh::Mesh<D> background = run_by_solver::build_mesh<D>(spec.mesh);
  if (spec.solver.implicit.basis != ImplicitBasis::Mesh)  // the Galerkin meshfree method
    return run_by_solver::run_meshfree<D>(spec, options, background);
  return run_by_solver::run_implicit_mpm<D>(spec, options, std::move(background));
}

}  // namespace

RunResult run_explicit(const Spec& spec, const RunOptions& options) {
#ifdef _OPENMP
  if (options.threads > 0) omp_set_num_threads(options.threads);
#endif
  if (spec.solver.is_implicit())
    return spec.grid.dim == 3 ? run_implicit_dim<3>(spec, options) : run_implicit_dim<2>(spec, options);
  switch (spec.grid.dim) {
    case 1:
      return run_by_solver::run_explicit_of_dim<1>(spec, options);
    case 3:
      return run_by_solver::run_explicit_of_dim<3>(spec, options);
    default:
      return run_by_solver::run_explicit_of_dim<2>(spec, options);
  }
}

std::string draw_plots(const std::filesystem::path& out_dir, const std::filesystem::path& scripts_dir) {
  return run_python_script(scripts_dir / "plot_history.py", {out_dir.string()});
}

}  // namespace matpoint
