#!/usr/bin/env bash
# `matpoint check` (and `run` before its first step) prints the step count and a rough wall time:
# end_time / dt steps (2.5 / 0.001 = 2500 here) of at most N particles, N an upper estimate from
# the bodies' bounding boxes: not below the 4 x 4 cells x 2 x 2 = 64 particles the run makes.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

cat >"$tmp/input.json" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3, 0.3], "max": [0.7, 0.7]}}],
  "solver": {"dt": 0.001, "end_time": 2.5}, "output": {"every_steps": 500, "plots": false} }
JSON
"$matpoint" check "$tmp/input.json" >"$tmp/check.out" 2>&1 || fail "check failed: $(cat "$tmp/check.out")"
grep -q "^estimate: about 2.5e+03 steps of dt = 0.001 x at most [0-9]* particles: roughly .* on one thread" "$tmp/check.out" ||
  fail "no step estimate in: $(cat "$tmp/check.out")"
bound=$(sed -n 's/^estimate: .* at most \([0-9]*\) particles.*/\1/p' "$tmp/check.out")
((bound >= 64 && bound <= 2 * 64)) || fail "the particle bound $bound is not an upper estimate of 64 within a factor 2"
"$matpoint" run "$tmp/input.json" --out "$tmp/out" >/dev/null 2>"$tmp/run.err" || fail "run failed: $(cat "$tmp/run.err")"
grep -q "^estimate: about 2.5e+03 steps" "$tmp/run.err" || fail "run printed no estimate: $(head -c 2000 "$tmp/run.err")"
steps=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["steps"])' "$tmp/out/summary.json")
[[ $steps -eq 2500 ]] || fail "the run took $steps steps, the estimate said 2500"
echo "PASS: check and run print the step estimate"
