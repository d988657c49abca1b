#!/usr/bin/env bash
# An input with exactly three different mistakes: `check` and `run` report all three, each with its
# JSON path, exit 2, and `run` writes nothing.
set -euo pipefail
matpoint=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cat >"$tmp/bad.json" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.05},
  "materials": [{"name": "m", "model": "linear_elastic", "density": -1000, "E": 1000, "nu": 0.5}],
  "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.5, 0.5], "radius": 0.2},
              "velocity": [0.1, 0]}],
  "solver": {"sceme": "usl", "dt": 0.001, "end_time": 0.05}, "output": {"every_steps": 10} }
JSON

status=0
"$matpoint" check "$tmp/bad.json" 2>"$tmp/check.err" >/dev/null || status=$?
[[ $status -eq 2 ]] || fail "matpoint check exited $status, expected 2; stderr: $(cat "$tmp/check.err")"
count=$(grep -c '^input error:' "$tmp/check.err" || true)
[[ $count -eq 3 ]] || fail "expected 3 'input error:' lines, got $count:"$'\n'"$(cat "$tmp/check.err")"
for path in 'materials[0].density' 'solver.sceme' 'materials[0].nu'; do
  grep '^input error:' "$tmp/check.err" | grep -qF "$path" || fail "no input error names $path:"$'\n'"$(cat "$tmp/check.err")"
done

status=0
"$matpoint" run "$tmp/bad.json" --quiet --out "$tmp/out" 2>"$tmp/run.err" >/dev/null || status=$?
[[ $status -eq 2 ]] || fail "matpoint run exited $status, expected 2"
count=$(grep -c '^input error:' "$tmp/run.err" || true)
[[ $count -eq 3 ]] || fail "run: expected 3 'input error:' lines, got $count"
[[ ! -e "$tmp/out/summary.json" ]] || fail "run on a bad input wrote summary.json"
if [[ -d "$tmp/out" ]] && [[ -n "$(ls -A "$tmp/out")" ]]; then
  fail "run on a bad input wrote into the output folder: $(ls -A "$tmp/out")"
fi
echo "PASS: three mistakes reported with their paths, exit 2, nothing written"
