#!/usr/bin/env bash
# SIGTERM stops a run cleanly: it finishes the step, writes checkpoint.h5 and the last output,
# summary.json says "interrupted", the exit status is 143 (128 + 15); the restart continues to the
# same results as the uninterrupted run. A truncated checkpoint is refused with exit 2.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
# shellcheck source=restart_common.bash
source "$(dirname "${BASH_SOURCE[0]}")/restart_common.bash"

interrupted_pair TERM
[[ $status == 143 ]] || fail "the terminated run exited with $status, expected 143; stderr: $(cat "$tmp/parts.stderr")"
grep -q -- "--restart" "$tmp/parts.stderr" || fail "stderr does not say how to continue: $(cat "$tmp/parts.stderr")"
"$python" - "$tmp/parts" <<'PY'
import json, sys, h5py
out = sys.argv[1]
s = json.load(open(f"{out}/summary.json"))
assert s["status"] == "interrupted" and s["exit_code"] == 143, (s["status"], s["exit_code"])
with h5py.File(f"{out}/checkpoint.h5", "r") as f:
    step = int(f["simulation/step"][0])
    assert step == s["steps"] == s["checkpoint_step"], (step, s["steps"], s["checkpoint_step"])
    assert f["particles/x"].shape == (s["particles"], 2)
rows = open(f"{out}/history.csv").read().splitlines()[1:]
assert rows[-1].split(",")[1] == str(step), "the last output is the interrupted step"
print(f"interrupted cleanly after step {step}")
PY

cp "$tmp/parts/checkpoint.h5" "$tmp/truncated.h5"
truncate -s $(($(stat -c %s "$tmp/truncated.h5") / 2)) "$tmp/truncated.h5"
status=0
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/bad" --restart "$tmp/truncated.h5" 2>"$tmp/bad.err" || status=$?
[[ $status -eq 2 ]] || fail "a truncated checkpoint gave exit $status, expected 2"
grep -q "not a usable checkpoint" "$tmp/bad.err" || fail "unclear message: $(cat "$tmp/bad.err")"

"$matpoint" run "$tmp/input.json" --quiet --threads 1 --out "$tmp/parts" --restart "$tmp/parts/checkpoint.h5" \
  >/dev/null 2>"$tmp/restart.err" || fail "restart failed: $(cat "$tmp/restart.err")"
same_results "$tmp/whole" "$tmp/parts"
echo "PASS: SIGTERM gave exit 143 with a usable checkpoint; the restart equals the uninterrupted run"
