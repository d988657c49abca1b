// The PETSc linear solver (implicit/petsc_solver.hpp), run by ctest on 1 and 2 ranks (label mpi):
//   - a nonsymmetric system (upwind convection-diffusion, 400 unknowns) whose exact solution x* is
//     chosen: GMRES + ASM/ILU(0) (the default), hypre BoomerAMG and MUMPS each reach x* within
//     cond2(A) times the relative residual asked of them (|x - x*| / |x*| <= cond2(A) |r| / |b|, the
//     standard residual bound), and agree with UMFPACK on the same rank to the same bound;
//   - new values on the same pattern reuse the matrix (one analysis), a new pattern re-creates it;
//   - a singular matrix is a failure with a message, not an exception or a hang.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <Eigen/SVD>
#include <cmath>
#include <string>
#include <vector>

#include "matpoint/core/parallel_session.hpp"
#include "matpoint/implicit/linear_solver.hpp"
#include "linear_test_systems.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;

using test::convection_diffusion;

Eigen::VectorXd chosen_solution(Eigen::Index n) {
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = std::sin(0.37 * static_cast<double>(i)) + 0.5;
  return x;
}

double condition_number(const SparseMatrix& a) {
  const Eigen::VectorXd s = Eigen::BDCSVD<Eigen::MatrixXd>(Eigen::MatrixXd(a)).singularValues();
  return s[0] / s[s.size() - 1];
}

/// PETSc options for one test, removed again at its end.
class ScopedPetscOptions {
 public:
  explicit ScopedPetscOptions(std::vector<std::pair<std::string, std::string>> options)
      : options_(std::move(options)) {
    for (const auto& [key, value] : options_)
      PetscOptionsSetValue(nullptr, key.c_str(), value.empty() ? nullptr : value.c_str());
  }
  ~ScopedPetscOptions() {
    for (const auto& [key, value] : options_) PetscOptionsClearValue(nullptr, key.c_str());
  }
  ScopedPetscOptions(const ScopedPetscOptions&) = delete;
  ScopedPetscOptions& operator=(const ScopedPetscOptions&) = delete;

 private:
  std::vector<std::pair<std::string, std::string>> options_;
};

struct Method {
  std::string name;
  std::vector<std::pair<std::string, std::string>> options;
};

class PetscMethods : public ::testing::TestWithParam<Method> {};

TEST_P(PetscMethods, SolveTheNonsymmetricSystemToTheResidualBound) {
  constexpr double kRelativeResidual = 1e-12;
  const ScopedPetscOptions options(GetParam().options);
  const SparseMatrix a = convection_diffusion(20);
  const Eigen::VectorXd x_exact = chosen_solution(a.rows());
  const Eigen::VectorXd b = a * x_exact;
  const double bound = condition_number(a) * kRelativeResidual;

  LinearSolverOptions petsc_options;
  petsc_options.kind = LinearSolverKind::Petsc;
  petsc_options.relative_tolerance = kRelativeResidual;
  const auto petsc = make_linear_solver(petsc_options);
  Eigen::VectorXd x;
  ASSERT_TRUE(petsc->factorize(a, 1)) << petsc->message();
  ASSERT_TRUE(petsc->solve(b, x)) << petsc->message();
  EXPECT_LT((x - x_exact).norm(), bound * x_exact.norm());

  const auto umfpack = make_linear_solver();
  Eigen::VectorXd x_umfpack;
  ASSERT_TRUE(umfpack->factorize(a, 1) && umfpack->solve(b, x_umfpack));
  EXPECT_LT((x - x_umfpack).norm(), bound * x_umfpack.norm());
  if (ParallelSession::rank() == 0)
    std::printf("[%s on %d ranks] |x - x*| / |x*| = %.2e, |x - x_umfpack| / |x_umfpack| = %.2e, bound %.2e\n",
              GetParam().name.c_str(), ParallelSession::size(), (x - x_exact).norm() / x_exact.norm(),
              (x - x_umfpack).norm() / x_umfpack.norm(), bound);

  // New values on the same pattern: no new analysis; the solution halves.
  ASSERT_TRUE(petsc->factorize(SparseMatrix(2.0 * a), 1)) << petsc->message();
  ASSERT_TRUE(petsc->solve(b, x)) << petsc->message();
  EXPECT_LT((x - 0.5 * x_exact).norm(), bound * 0.5 * x_exact.norm());
  EXPECT_EQ(petsc->stats().analyses, 1);
  // A new pattern (another size): the matrix, vectors and KSP are made again.
  const SparseMatrix small = convection_diffusion(7);
  const Eigen::VectorXd x_small = chosen_solution(small.rows());
  ASSERT_TRUE(petsc->factorize(small, 2)) << petsc->message();
  ASSERT_TRUE(petsc->solve(small * x_small, x)) << petsc->message();
  EXPECT_LT((x - x_small).norm(), condition_number(small) * kRelativeResidual * x_small.norm());
  EXPECT_EQ(petsc->stats().analyses, 2);
}

INSTANTIATE_TEST_SUITE_P(
    Default, PetscMethods,
    ::testing::Values(Method{"gmres_asm_ilu0", {}},
                      Method{"gmres_boomeramg", {{"-pc_type", "hypre"}, {"-pc_hypre_type", "boomeramg"}}},
                      Method{"mumps", {{"-ksp_type", "preonly"}, {"-pc_type", "lu"},
                                       {"-pc_factor_mat_solver_type", "mumps"}}}),
    [](const auto& info) { return info.param.name; });

TEST(PetscSolver, SingularMatrixIsAFailureNotAnException) {
  SparseMatrix a(4, 4);
  for (int i = 0; i < 4; ++i) a.insert(i, 0) = 1.0 + i;  // rank 1
  for (int i = 1; i < 4; ++i) a.insert(i, i) = 0.0;      // a full diagonal pattern, zero values
  a.makeCompressed();
  LinearSolverOptions options;
  options.kind = LinearSolverKind::Petsc;
  options.max_iterations = 50;
  const auto solver = make_linear_solver(options);
  Eigen::VectorXd x;
  const bool solved = solver->factorize(a, 1) && solver->solve(Eigen::Vector4d(1, 2, 3, 4), x);
  EXPECT_FALSE(solved);
  EXPECT_FALSE(solver->message().empty());
  if (ParallelSession::rank() == 0) std::printf("singular: %s\n", solver->message().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const matpoint::ParallelSession session({});
  // Only rank 0 prints gtest's report (every rank runs every test: the solves are collective).
  if (matpoint::ParallelSession::rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failures = RUN_ALL_TESTS();
  int any = failures;
  MPI_Allreduce(&failures, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return any != 0 ? 1 : 0;
}
