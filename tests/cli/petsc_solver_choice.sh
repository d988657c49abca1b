#!/usr/bin/env bash
# solver.implicit.linear_solver "petsc": a build without PETSc (the default) refuses it before any work
# (exit 2, the JSON path, the value, what to do) and refuses PETSc options after `--` the same way; a
# build with PETSc (MATPOINT_PETSC_BUILD=1, set by tests/CMakeLists.txt) accepts both and runs the
# static cantilever (h = 0.5 m) to the deflection of its check (-0.599659 m, total-Lagrangian FEM).
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
root=$2
sed 's/"analysis": "static"/"analysis": "static", "linear_solver": "petsc"/' \
  "$root/examples/cantilever-static/input.json" >"$tmp/petsc.json"
grep -q '"linear_solver": "petsc"' "$tmp/petsc.json" || fail "could not set linear_solver in the example"

if [[ ${MATPOINT_PETSC_BUILD:-0} != 1 ]]; then
  status=0
  "$matpoint" check "$tmp/petsc.json" 2>"$tmp/check.err" >/dev/null || status=$?
  [[ $status -eq 2 ]] || fail "check exited $status, expected 2: $(cat "$tmp/check.err")"
  grep '^input error:' "$tmp/check.err" | grep -F 'solver.implicit.linear_solver' | grep -F '"petsc"' |
    grep -qF 'MATPOINT_PETSC' || fail "the error does not name the path, the value and the build option: $(cat "$tmp/check.err")"
  status=0
  "$matpoint" run "$tmp/petsc.json" --quiet --out "$tmp/out" 2>"$tmp/run.err" >/dev/null || status=$?
  [[ $status -eq 2 ]] || fail "run exited $status, expected 2"
  [[ ! -e "$tmp/out/summary.json" ]] || fail "a refused run wrote summary.json"
  status=0
  "$matpoint" run "$root/examples/cantilever-static/input.json" --quiet --out "$tmp/out2" -- -ksp_type cg \
    2>"$tmp/opts.err" >/dev/null || status=$?
  [[ $status -eq 2 ]] || fail "PETSc options in a serial build: exit $status, expected 2"
  grep -qF 'MATPOINT_PETSC' "$tmp/opts.err" || fail "no hint at the PETSc build: $(cat "$tmp/opts.err")"
  echo "PASS: a build without PETSc refuses \"petsc\" and PETSc options with exit 2"
  exit 0
fi

"$matpoint" run "$tmp/petsc.json" --quiet --out "$tmp/out" -- -ksp_rtol 1e-12 >/dev/null ||
  fail "the PETSc run failed"
"$python" - "$tmp/out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["implicit"]["linear_solver"] == "petsc", s["implicit"]
checks = s["checks"]
assert checks and all(c["pass"] for c in checks), checks
print("PASS: PETSc solves the cantilever:", [c["measured"] for c in checks])
PY
