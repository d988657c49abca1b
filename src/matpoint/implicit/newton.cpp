#include "matpoint/implicit/newton.hpp"

#include <cmath>

namespace matpoint::implicit {

namespace {

/// |x_c| for every component c (entries k with k % components == c).
Eigen::VectorXd component_norms(const Eigen::VectorXd& x, int components) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(components);
  for (Eigen::Index k = 0; k < x.size(); ++k) s[k % components] += x[k] * x[k];
  return s.cwiseSqrt();
}

bool increment_converged(const Eigen::VectorXd& du, const Eigen::VectorXd& u, const NewtonOptions& o) {
  const Eigen::VectorXd dn = component_norms(du, o.components), un = component_norms(u, o.components);
  for (int c = 0; c < o.components; ++c)
    if (!(un[c] < o.displacement_floor || dn[c] <= o.increment_tolerance * un[c])) return false;
  return true;
}

/// |R_k| is below round_off_relative |R_0| and the last iteration did not halve it.
bool stalled_at_round_off(const std::vector<NewtonIteration>& history, double rn, double r0,
                          const NewtonOptions& o) {
  return !history.empty() && rn <= o.round_off_relative * r0 && rn > 0.5 * history.back().residual_norm;
}

}  // namespace

std::string_view newton_status_name(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::Converged:
      return "converged";
    case NewtonStatus::MaxIterations:
      return "no convergence within the iteration limit";
    case NewtonStatus::Diverged:
      return "diverged";
    case NewtonStatus::NotFinite:
      return "non-finite residual or increment";
    case NewtonStatus::LinearSolveFailed:
      return "linear solve failed";
    case NewtonStatus::AssemblyFailed:
      return "assembly failed";
  }
  return "unknown";
}

NewtonResult newton_solve(const AssembleFunction& assemble, std::uint64_t pattern_version,
                          LinearSolver& solver, Eigen::VectorXd& u, const NewtonOptions& o) {
  NewtonResult result;
  Eigen::VectorXd R, du, trial, R_trial;
  SparseMatrix K;
  double r0 = -1.0;
  const auto fail = [&](NewtonStatus s, std::string message) {
    result.status = s;
    result.message = std::move(message);
    return result;
  };
  for (int k = 0;; ++k) {
    if (!assemble(u, R, &K)) return fail(NewtonStatus::AssemblyFailed, "assembly failed");
    const double rn = R.norm();
    result.final_residual_norm = rn;
    if (!std::isfinite(rn)) return fail(NewtonStatus::NotFinite, "residual is not finite");
    if (r0 < 0.0) r0 = rn;
    if (rn > o.divergence_factor * (r0 + 1e-300))
      return fail(NewtonStatus::Diverged, "residual grew past the limit");
    const double residual_target = std::max(o.residual_absolute, o.residual_relative * r0);
    if (residual_target > 0.0 && rn <= residual_target) {
      result.status = NewtonStatus::Converged;
      return result;
    }
    if (stalled_at_round_off(result.history, rn, r0, o)) {
      result.status = NewtonStatus::Converged;
      result.round_off_stop = true;
      return result;
    }
    if (k == o.max_iterations) return fail(NewtonStatus::MaxIterations, "no convergence");
    if (!solver.factorize(K, pattern_version)) return fail(NewtonStatus::LinearSolveFailed, solver.message());
    if (!solver.solve(-R, du)) return fail(NewtonStatus::LinearSolveFailed, solver.message());
    if (!du.allFinite()) return fail(NewtonStatus::NotFinite, "Newton increment is not finite");
    double step = 1.0;
    if (o.line_search) {
      // Backtracking (Armijo on |R|): halve until |R(u + s du)| <= (1 - 1e-4 s) |R(u)|.
      for (int h = 0; h <= o.line_search_max_halvings; ++h) {
        trial = u + step * du;
        if (assemble(trial, R_trial, nullptr) && std::isfinite(R_trial.norm()) &&
            R_trial.norm() <= (1.0 - 1e-4 * step) * rn)
          break;
        if (h < o.line_search_max_halvings) step *= 0.5;
      }
    }
    du *= step;
    u += du;
    result.history.push_back({rn, du.norm(), step});
    if (increment_converged(du, u, o)) {
      // The residual at the converged u, for the history (no Jacobian needed).
      if (assemble(u, R, nullptr)) result.final_residual_norm = R.norm();
      result.status = NewtonStatus::Converged;
      return result;
    }
  }
}

}  // namespace matpoint::implicit
