#include "matpoint/core/parallel_session.hpp"

#include <stdexcept>

#ifdef MATPOINT_HAS_PETSC
#include <petscsys.h>
#endif

namespace matpoint {

#ifdef MATPOINT_HAS_PETSC

ParallelSession::ParallelSession(const std::vector<std::string>& petsc_options) {
  PetscBool initialised = PETSC_FALSE;
  PetscInitialized(&initialised);
  if (initialised == PETSC_TRUE) return;
  // PETSc's options come from the words after `--` (argv-style, behind a program name) and from
  // PETSC_OPTIONS; matpoint's own command line never reaches PETSc, whose parser would misread it.
  std::vector<std::string> words{"matpoint"};
  words.insert(words.end(), petsc_options.begin(), petsc_options.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(words.size());
  char** argv_pointer = argv.data();
  // matpoint handles SIGINT/SIGTERM itself (core/interrupt.hpp: finish the step, checkpoint, exit
  // 128 + signal); PETSc's handlers would abort instead. Set before PetscInitialize, as PETSc allows.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  if (PetscInitialize(&argc, &argv_pointer, nullptr, nullptr) != 0)
    throw std::runtime_error("PETSc (and MPI) failed to initialise");
  started_ = true;
}

ParallelSession::~ParallelSession() {
  if (started_) PetscFinalize();
}

int ParallelSession::rank() {
  if (!petsc_running()) return 0;
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

int ParallelSession::size() {
  if (!petsc_running()) return 1;
  int n = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &n);
  return n;
}

bool ParallelSession::built_with_petsc() { return true; }

bool ParallelSession::petsc_running() {
  PetscBool initialised = PETSC_FALSE;
  PetscInitialized(&initialised);
  return initialised == PETSC_TRUE;
}

#else  // the serial build

ParallelSession::ParallelSession(const std::vector<std::string>& petsc_options) {
  if (!petsc_options.empty())
    throw std::runtime_error("PETSc options after `--` (\"" + petsc_options.front() +
                             "\" ...) need a build with PETSc: cmake -DMATPOINT_PETSC=ON, or scripts/setup.sh --mpi");
}
ParallelSession::~ParallelSession() = default;
int ParallelSession::rank() { return 0; }
int ParallelSession::size() { return 1; }
bool ParallelSession::built_with_petsc() { return false; }
bool ParallelSession::petsc_running() { return false; }

#endif

}  // namespace matpoint
