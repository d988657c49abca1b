#!/usr/bin/env bash
# `matpoint verify` (Gong 2015 manufactured solutions): the 1-D checks pass with exit 0, --json prints
# a list of {name, method, measured, expected, tolerance, pass}, plots/convergence_*.csv is written;
# a run stopped by a guard (det F <= 0, a particle leaving the grid) where convergence is expected
# (CPDI at G = 0.35: the exact F itself reaches 1 - 0.35 pi < 0) stops cleanly with exit 3; a bad
# name exits 2.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

status=0
"$matpoint" verify mms-1d --json --out "$tmp" >"$tmp/json" 2>"$tmp/stderr" || status=$?
[[ $status -eq 0 ]] || fail "verify mms-1d exited $status:"$'\n'"$(cat "$tmp/json" "$tmp/stderr")"
"$python" - "$tmp/json" <<'PY' || fail "bad --json output: $(cat "$tmp/json")"
import json, sys
checks = json.load(open(sys.argv[1]))
assert isinstance(checks, list) and len(checks) >= 8, checks
for c in checks:
    for key in ("name", "method", "measured", "expected", "tolerance", "pass"):
        assert key in c, (key, c)
    assert c["pass"] is True, c
PY
ls "$tmp"/plots/convergence_mms-1d_linear_G_0.0001.csv >/dev/null || fail "no convergence csv"

status=0
"$matpoint" verify mms-1d --shape cpdi1 --amplitude 0.35 --cells 8 --no-plots >"$tmp/out" 2>&1 || status=$?
[[ $status -eq 3 ]] || fail "a diverging run: expected exit 3, got $status:"$'\n'"$(cat "$tmp/out")"
grep -q "DIVERGED: numerical failure at step" "$tmp/out" || fail "no divergence message:"$'\n'"$(cat "$tmp/out")"

status=0
"$matpoint" verify mms-9d >"$tmp/out" 2>&1 || status=$?
[[ $status -eq 2 ]] || fail "a bad name: expected exit 2, got $status"
echo "ok"
