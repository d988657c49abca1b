// Newton's method on an assembled nonlinear system R(u) = 0, generic over the formulation: the
// caller gives a callback that assembles R (and the Jacobian K = dR/du when asked) at u, and a
// linear solver. Stopping rules (Aulisa & Capodaglio §3.3; tolerances from the authors' code, the
// extraction's A16):
//   - increment test: for every displacement component c, |du_c| / |u_c| < increment_tolerance
//     (1e-9); a component whose |u_c| is below displacement_floor (1e-13, as the code) counts as
//     converged; dof k belongs to component k % components (node-major numbering);
//   - optional residual test: |R| <= max(residual_absolute, residual_relative |R_0|);
//   - round-off stop: once |R_k| <= round_off_relative |R_0| (1e-6, a hundred times below Kratos'
//     default residual test 1e-4 |R_0|, Iaconeta extraction A7) an iteration that does not halve
//     |R| ends Newton as converged (flagged): quadratic convergence from there would reach
//     round-off in one more step, so a residual that stops falling is at the floor set by the
//     cancellation in the internal force (or a non-smooth contact term), and more iterations only
//     wander (seen: GMM-MLS rolling disk, |R| 985 -> 3e-9 then the increment test never met);
//   - at most max_iterations (20) linear solves.
// Optional backtracking line search on |R|. Numerical trouble (NaN, divergence, a singular or failed
// linear solve, a failed assembly) ends with a failure status, never with an exception.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "matpoint/implicit/linear_solver.hpp"

namespace matpoint::implicit {

struct NewtonOptions {
  int max_iterations = 20;
  double increment_tolerance = 1e-9;
  double displacement_floor = 1e-13;
  int components = 1;
  double residual_absolute = 0.0;  // 0 with residual_relative = 0: no residual test
  double residual_relative = 0.0;
  double round_off_relative = 1e-6;  // 0: no round-off stop
  double divergence_factor = 1e12;  // |R| > divergence_factor (|R_0| + tiny): diverged
  bool line_search = false;
  int line_search_max_halvings = 10;
};

struct NewtonIteration {
  double residual_norm = 0.0;   // |R(u_k)| before the solve
  double increment_norm = 0.0;  // |du_k| (times the step length)
  double step_length = 1.0;     // line-search factor
};

enum class NewtonStatus { Converged, MaxIterations, Diverged, NotFinite, LinearSolveFailed, AssemblyFailed };
std::string_view newton_status_name(NewtonStatus status);

struct NewtonResult {
  NewtonStatus status = NewtonStatus::MaxIterations;
  std::vector<NewtonIteration> history;
  double final_residual_norm = 0.0;  // |R| at the returned u (when it was assembled)
  bool round_off_stop = false;       // converged by the round-off stop (not the increment test)
  std::string message;
  [[nodiscard]] bool converged() const { return status == NewtonStatus::Converged; }
  [[nodiscard]] int iterations() const { return static_cast<int>(history.size()); }
};

/// assemble(u, R, K): R(u) and, when K is not null, K(u); returns false on failure. pattern_version:
/// the linear solver's key for reusing its symbolic analysis (SparseAssembly::pattern_version()).
using AssembleFunction = std::function<bool(const Eigen::VectorXd& u, Eigen::VectorXd& R, SparseMatrix* K)>;

/// Solves R(u) = 0 starting from u (updated in place).
NewtonResult newton_solve(const AssembleFunction& assemble, std::uint64_t pattern_version,
                          LinearSolver& solver, Eigen::VectorXd& u, const NewtonOptions& options = {});

}  // namespace matpoint::implicit
