#!/usr/bin/env bash
# Traps around output folders: a fresh run refuses a folder holding another run's outputs unless
# --overwrite (which deletes only matpoint's files); an interrupted run prints the full command to
# continue, which works from any folder; --restart without --out continues in the checkpoint's
# folder; a restart from a checkpoint older than the run that finished in its folder is refused.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
# shellcheck source=restart_common.bash
source "$(dirname "${BASH_SOURCE[0]}")/restart_common.bash"
matpoint=$(realpath "$matpoint")  # the commands below run from other folders

# --- a folder of another run -------------------------------------------------------------------
cat >"$tmp/small.json" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3, 0.3], "max": [0.7, 0.7]},
              "velocity": [0.1, 0]}],
  "solver": {"dt": 0.001, "end_time": 0.01}, "output": {"every_steps": 5, "plots": false} }
JSON
"$matpoint" run "$tmp/small.json" --quiet --out "$tmp/out" >/dev/null 2>&1 || fail "first run failed"
before=$(cksum "$tmp/out/summary.json")
status=0
"$matpoint" run "$tmp/small.json" --quiet --out "$tmp/out" >/dev/null 2>"$tmp/err" || status=$?
[[ $status -eq 2 ]] || fail "a run into another run's folder exited $status, expected 2"
grep -q "already holds the outputs of another run" "$tmp/err" || fail "unclear refusal: $(cat "$tmp/err")"
grep -q -- "--overwrite" "$tmp/err" || fail "the refusal does not name --overwrite: $(cat "$tmp/err")"
[[ $(cksum "$tmp/out/summary.json") == "$before" ]] || fail "the refused run changed summary.json"

touch "$tmp/out/particles_000099.vtu" "$tmp/out/my notes.txt"
"$matpoint" run "$tmp/small.json" --quiet --out "$tmp/out" --overwrite >/dev/null 2>"$tmp/err" ||
  fail "--overwrite run failed: $(cat "$tmp/err")"
grep -q "deleted .* output file(s) of an earlier run" "$tmp/err" || fail "--overwrite did not say so: $(cat "$tmp/err")"
[[ ! -e "$tmp/out/particles_000099.vtu" ]] || fail "--overwrite left a stale particles_000099.vtu"
[[ -e "$tmp/out/my notes.txt" ]] || fail "--overwrite deleted a file that is not matpoint's"

# --- the printed continue command, run from another folder -------------------------------------
restart_input "$tmp/input.json"
status=finished
for attempt in 1 2 3; do
  rm -rf "$tmp/parts"
  status=$(run_until_checkpoint INT "$tmp/input.json" "$tmp/parts")
  [[ $status == finished ]] || break
done
[[ $status == 130 ]] || fail "the interrupted run exited $status, expected 130"
command=$(sed -n 's/^the whole command: matpoint //p' "$tmp/parts.stderr")
[[ $command == *"--out "* ]] || fail "the continue command has no --out: $(cat "$tmp/parts.stderr")"
mkdir "$tmp/elsewhere"
(cd "$tmp/elsewhere" && eval "\"\$matpoint\" $command --quiet") >/dev/null 2>"$tmp/err" ||
  fail "the printed command failed: $command: $(cat "$tmp/err")"
[[ ! -e "$tmp/elsewhere/out" ]] || fail "the printed command wrote into ./out"
"$python" -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["status"]=="ok", s["status"]' \
  "$tmp/parts/summary.json" || fail "the continued run did not finish in the checkpoint's folder"

# --- --restart without --out; a stale checkpoint -----------------------------------------------
for attempt in 1 2 3; do
  rm -rf "$tmp/p2"
  status=$(run_until_checkpoint INT "$tmp/input.json" "$tmp/p2")
  [[ $status == finished ]] || break
done
[[ $status == 130 ]] || fail "the second interrupted run exited $status, expected 130"
checkpoint_step=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["checkpoint_step"])' "$tmp/p2/summary.json")
# The same physics without a checkpoint schedule: the finished run writes no checkpoint.
sed 's/, "checkpoint": {"every_steps": 100}//' "$tmp/input.json" >"$tmp/no_checkpoints.json"
(cd "$tmp/elsewhere" && "$matpoint" run "$tmp/no_checkpoints.json" --quiet --restart "$tmp/p2/checkpoint.h5") \
  >/dev/null 2>"$tmp/err" || fail "restart without --out failed: $(cat "$tmp/err")"
[[ ! -e "$tmp/elsewhere/out" ]] || fail "--restart without --out wrote into ./out, not the checkpoint's folder"
finished_step=$("$python" -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["status"]=="ok"; print(s["steps"])' \
  "$tmp/p2/summary.json") || fail "the restart did not finish in the checkpoint's folder"
sed 's/"end_time": 3.0/"end_time": 4.0/' "$tmp/no_checkpoints.json" >"$tmp/longer.json"
status=0
"$matpoint" run "$tmp/longer.json" --quiet --restart "$tmp/p2/checkpoint.h5" >/dev/null 2>"$tmp/err" || status=$?
[[ $status -eq 2 ]] || fail "a restart from a stale checkpoint exited $status, expected 2"
grep -q "checkpoint of step $checkpoint_step, older than the run that finished .* at step $finished_step" "$tmp/err" ||
  fail "the refusal does not name both steps ($checkpoint_step, $finished_step): $(cat "$tmp/err")"
echo "PASS: foreign run folders refused, --overwrite clears only ours, restart commands complete, stale checkpoints refused"
