#!/usr/bin/env bash
# Installs the Debian packages matpoint needs (only those missing), then builds Release into build/.
# Safe to run again: it installs nothing and rebuilds only what changed.
# With --mpi: also OpenMPI and PETSc (libopenmpi-dev, openmpi-bin, libpetsc-real-dev, pkg-config),
# and a second build with -DMATPOINT_PETSC=ON into build-mpi/ (docs/user_guide.md "MPI and PETSc").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# zlib1g-dev: compressed .vtu output; libgmsh-dev: Gmsh .msh mesh import (src/matpoint/mesh);
# python3-vtk9 and python3-meshio: the tests read our .vtu files back with VTK's own reader and with
# meshio. (libfmt-dev was listed once but never used.) libsuitesparse-dev: UMFPACK and KLU, the
# implicit solver's sparse direct solvers (src/matpoint/implicit/linear_solver.cpp).
packages=(build-essential cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libhdf5-dev zlib1g-dev libgmsh-dev
          libsuitesparse-dev
          libgtest-dev libgmock-dev libbenchmark-dev
          python3 python3-matplotlib python3-numpy python3-meshio python3-h5py python3-vtk9)

mpi=0
[[ ${1:-} == --mpi ]] && mpi=1
((mpi)) && packages+=(libopenmpi-dev openmpi-bin libpetsc-real-dev pkg-config)

bash scripts/install_packages.sh "${packages[@]}"

# Build output goes to a log: quiet when all is well, shown in full when something fails.
log=$(mktemp)
trap 'rm -f "$log"' EXIT

echo "setup: building Release into build/"
if ! { cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j"$(nproc)"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "setup: build failed (output above)" >&2
  exit 1
fi
echo "setup: build/matpoint is ready"
((mpi)) || exit 0
echo "setup: building Release with MPI and PETSc into build-mpi/"
if ! { cmake -S . -B build-mpi -DCMAKE_BUILD_TYPE=Release -DMATPOINT_PETSC=ON &&
       cmake --build build-mpi -j"$(nproc)"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "setup: MPI build failed (output above)" >&2
  exit 1
fi
echo "setup: build-mpi/matpoint is ready (mpirun -n P build-mpi/matpoint run ...)"
