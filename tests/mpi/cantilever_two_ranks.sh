#!/usr/bin/env bash
# Issue 23, verification 5: an implicit case solved with PETSc KSP on 2 ranks gives the serial
# SuiteSparse answer. The static cantilever (examples/cantilever-static, h = 0.5 m, Iaconeta 2017
# §5.1) with UMFPACK on one process, and with "petsc" (GMRES + ASM/ILU(0), -ksp_rtol 1e-12) under
# mpirun -n 2: Point A's deflection agrees to the Newton increment tolerance (1e-9 relative,
# solver.implicit.newton), both meet the example's check (-0.599659 m, total-Lagrangian FEM), and
# rank 1 writes the same result into its own folder (OUT.rank1); rank 0 (only) notes that every rank
# runs the whole simulation.
source "$(dirname "${BASH_SOURCE[0]}")/../cli/common.bash"
root=$2
mpiexec=$3
example="$root/examples/cantilever-static/input.json"
sed 's/"analysis": "static"/"analysis": "static", "linear_solver": "petsc"/' "$example" >"$tmp/petsc.json"

"$matpoint" run "$example" --quiet --out "$tmp/umfpack" >/dev/null || fail "the UMFPACK run failed"
"$mpiexec" -n 2 "$matpoint" run "$tmp/petsc.json" --quiet --out "$tmp/petsc" -- -ksp_rtol 1e-12 >"$tmp/mpi.log" 2>&1 ||
  fail "mpirun -n 2 failed: $(tail -20 "$tmp/mpi.log")"
[[ -f "$tmp/petsc.rank1/summary.json" ]] || fail "rank 1 wrote no summary into petsc.rank1"
grep -q "every rank runs the whole simulation" "$tmp/mpi.log" ||
  fail "rank 0 did not say that every rank runs the whole simulation: $(head -5 "$tmp/mpi.log")"
[[ $(grep -c "every rank runs the whole simulation" "$tmp/mpi.log") == 1 ]] || fail "the note came from more than rank 0"

"$python" - "$tmp/umfpack/summary.json" "$tmp/petsc/summary.json" "$tmp/petsc.rank1/summary.json" <<'PY'
import json, sys
serial, rank0, rank1 = (json.load(open(p)) for p in sys.argv[1:])
assert rank0["implicit"]["linear_solver"] == "petsc" and serial["implicit"]["linear_solver"] == "umfpack"
value = lambda s: s["checks"][0]["measured"]
for s in (serial, rank0, rank1):
    assert s["checks"][0]["pass"], s["checks"]
difference = abs(value(rank0) - value(serial)) / abs(value(serial))
assert difference <= 1e-9, (value(rank0), value(serial))
assert value(rank1) == value(rank0), (value(rank1), value(rank0))
print(f"PASS: Point A {value(rank0):.12f} m (petsc, 2 ranks) vs {value(serial):.12f} m (umfpack), "
      f"relative difference {difference:.1e}; Krylov iterations {rank0['implicit']['krylov_iterations']}")
PY
