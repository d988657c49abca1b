#!/usr/bin/env bash
# Installs what is missing (OpenMPI and PETSc too), builds build-mpi/ with -DMATPOINT_PETSC=ON and runs
# the MPI tests (label mpi: the PETSc solver on 1 and 2 ranks, the cantilever on 2 ranks) and the
# command-line tests of that build. Not part of the default suite (scripts/test.sh): the serial
# build stays the default. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh --mpi
ctest --test-dir build-mpi --output-on-failure -j2 -R '^(mpi|cli)\.' "$@"
