#!/usr/bin/env bash
# A run killed with SIGKILL at a random step (after its first checkpoint) and restarted from its
# last checkpoint ends bit for bit where the uninterrupted run ends (one thread): every .vtu file,
# results.pvd and history.csv are identical, without a missing or repeated row.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
# shellcheck source=restart_common.bash
source "$(dirname "${BASH_SOURCE[0]}")/restart_common.bash"

interrupted_pair KILL
[[ $status == 137 ]] || fail "the killed run exited with $status, expected 137 (SIGKILL)"
[[ -s "$tmp/parts/checkpoint.h5" ]] || fail "no checkpoint.h5 after the kill"

"$matpoint" run "$tmp/input.json" --quiet --threads 1 --out "$tmp/parts" --restart "$tmp/parts/checkpoint.h5" \
  >/dev/null 2>"$tmp/restart.err" || fail "restart failed: $(cat "$tmp/restart.err")"
same_results "$tmp/whole" "$tmp/parts"
step=$("$python" -c 'import json, sys; print(json.load(open(sys.argv[1]))["restarted_at_step"])' "$tmp/parts/summary.json")
((step > 0 && step < 3000)) || fail "restarted at step $step, expected one inside the run"
echo "PASS: killed after step >= $step, restarted, and the results equal the uninterrupted run's bit for bit"
