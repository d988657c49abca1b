#include "matpoint/implicit/linear_solver.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/KLUSupport>
#include <Eigen/UmfPackSupport>
#include <chrono>
#include <stdexcept>
#include <unsupported/Eigen/IterativeSolvers>

#include "matpoint/implicit/petsc_solver.hpp"

namespace matpoint::implicit {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A direct solver of Eigen's sparse interface (UmfPackLU, KLU).
template <class Direct>
class DirectSolver final : public LinearSolver {
 public:
  explicit DirectSolver(std::string_view name) : name_(name) {}
  [[nodiscard]] std::string_view name() const override { return name_; }

 protected:
  bool analyze(const SparseMatrix& K) override {
    solver_.analyzePattern(K);
    return check("symbolic analysis");
  }
  bool factorize_numeric(const SparseMatrix& K) override {
    solver_.factorize(K);
    return check("factorisation (singular matrix?)");
  }
  bool solve_with(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = solver_.solve(b);
    return check("solve") && x.allFinite();
  }

 private:
  bool check(const char* what) {
    if (solver_.info() == Eigen::Success) return true;
    message_ = std::string(name_) + ": " + what + " failed";
    return false;
  }
  std::string_view name_;
  Direct solver_;
};

/// A Krylov solver with an IncompleteLUT preconditioner (BiCGSTAB, GMRES).
template <class Krylov>
class KrylovSolver final : public LinearSolver {
 public:
  KrylovSolver(std::string_view name, const LinearSolverOptions& o) : name_(name) {
    solver_.setTolerance(o.relative_tolerance);
    solver_.setMaxIterations(o.max_iterations);
    solver_.preconditioner().setDroptol(o.ilut_drop_tolerance);
    solver_.preconditioner().setFillfactor(o.ilut_fill_factor);
    if constexpr (requires { solver_.set_restart(1); }) solver_.set_restart(o.gmres_restart);
  }
  [[nodiscard]] std::string_view name() const override { return name_; }

 protected:
  bool analyze(const SparseMatrix& K) override {
    // No info() check here: Eigen 3.4's IncompleteLUT leaves its status uninitialised until the
    // first factorize(), so the solver's info() after analyzePattern() is undefined (it read as a
    // failure on the implicit MPM matrices).
    solver_.analyzePattern(K);
    return true;
  }
  bool factorize_numeric(const SparseMatrix& K) override {
    solver_.factorize(K);
    return check("incomplete LU factorisation");
  }
  bool solve_with(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = solver_.solve(b);
    stats_.krylov_iterations += solver_.iterations();
    if (solver_.info() != Eigen::Success || !x.allFinite()) {
      message_ = std::string(name_) + ": no convergence in " + std::to_string(solver_.iterations()) +
                 " iterations (relative residual " + std::to_string(solver_.error()) + ")";
      return false;
    }
    return true;
  }

 private:
  bool check(const char* what) {
    if (solver_.info() == Eigen::Success) return true;
    message_ = std::string(name_) + ": " + what + " failed";
    return false;
  }
  std::string_view name_;
  Krylov solver_;
};

}  // namespace

bool LinearSolver::factorize(const SparseMatrix& K, std::uint64_t pattern_version) {
  message_.clear();
  if (!analyzed_ || pattern_version != analyzed_version_) {
    const auto t0 = std::chrono::steady_clock::now();
    analyzed_ = analyze(K);
    stats_.analyze_seconds += seconds_since(t0);
    ++stats_.analyses;
    if (!analyzed_) return false;
    analyzed_version_ = pattern_version;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = factorize_numeric(K);
  stats_.factorize_seconds += seconds_since(t0);
  ++stats_.factorizations;
  return ok;
}

bool LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = solve_with(b, x);
  stats_.solve_seconds += seconds_since(t0);
  ++stats_.solves;
  return ok;
}

std::string_view linear_solver_name(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::Umfpack:
      return "umfpack";
    case LinearSolverKind::Klu:
      return "klu";
    case LinearSolverKind::BicgstabIlut:
      return "bicgstab_ilut";
    case LinearSolverKind::GmresIlut:
      return "gmres_ilut";
    case LinearSolverKind::Petsc:
      return "petsc";
  }
  return "unknown";
}

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options) {
  const std::string_view name = linear_solver_name(options.kind);
  switch (options.kind) {
    case LinearSolverKind::Umfpack:
      return std::make_unique<DirectSolver<Eigen::UmfPackLU<SparseMatrix>>>(name);
    case LinearSolverKind::Klu:
      return std::make_unique<DirectSolver<Eigen::KLU<SparseMatrix>>>(name);
    case LinearSolverKind::BicgstabIlut:
      return std::make_unique<KrylovSolver<Eigen::BiCGSTAB<SparseMatrix, Eigen::IncompleteLUT<double>>>>(
          name, options);
    case LinearSolverKind::GmresIlut:
      return std::make_unique<KrylovSolver<Eigen::GMRES<SparseMatrix, Eigen::IncompleteLUT<double>>>>(
          name, options);
    case LinearSolverKind::Petsc:
      if (auto petsc = make_petsc_solver(options)) return petsc;
      throw std::runtime_error("linear solver \"petsc\": this build lacks PETSc (cmake -DMATPOINT_PETSC=ON)");
  }
  return nullptr;
}

}  // namespace matpoint::implicit
