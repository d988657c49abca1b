# Shared by the restart tests (sourced; not a test itself: the test glob is *.sh). Needs common.bash.
# restart_input FILE: a 2-D two-disk collision of ~1600 particles and 3000 steps (about a second on
# one thread), outputs every 100 steps and a checkpoint every 100 steps, and a probe (its history
# columns go through the checkpoint too).
restart_input() {
  cat >"$1" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.025},
  "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.25, 0.25], "radius": 0.2},
              "velocity": [0.1, 0.1]},
             {"material": "m", "shape": {"type": "disk", "center": [0.75, 0.75], "radius": 0.2},
              "velocity": [-0.1, -0.1]}],
  "solver": {"scheme": "musl", "basis": "bspline2", "dt": 0.001, "end_time": 3.0},
  "output": {"every_steps": 100, "plots": false, "checkpoint": {"every_steps": 100},
             "probes": [{"name": "centre", "position": [0.25, 0.25]}]} }
JSON
}

# run_until_checkpoint SIGNAL INPUT OUT: starts a run, waits for its first checkpoint, waits a
# random 0 to 0.5 s more, sends SIGNAL and echoes the exit status ("finished" when the run ended
# before the signal could reach it).
run_until_checkpoint() {
  local signal=$1 input=$2 out=$3 status=0
  "$matpoint" run "$input" --quiet --threads 1 --out "$out" >"$out.stdout" 2>"$out.stderr" &
  local pid=$!
  while [[ ! -e "$out/checkpoint.h5" ]] && kill -0 "$pid" 2>/dev/null; do sleep 0.02; done
  sleep "$(printf '0.%02d' $((RANDOM % 50)))"
  if ! kill "-$signal" "$pid" 2>/dev/null; then
    wait "$pid" || true
    echo finished
    return
  fi
  wait "$pid" || status=$?
  if ((status == 0)); then echo finished; else echo "$status"; fi
}

# same_results A B: every .vtu file, results.pvd and history.csv of two output folders are identical.
same_results() {
  local a=$1 b=$2 file
  for file in "$a"/particles_*.vtu "$a/results.pvd" "$a/history.csv"; do
    cmp -s "$file" "$b/$(basename "$file")" || fail "$(basename "$file") differs from the uninterrupted run's"
  done
  [[ $(ls "$a"/particles_*.vtu | wc -l) -eq $(ls "$b"/particles_*.vtu | wc -l) ]] || fail "different .vtu counts"
}

# interrupted_pair SIGNAL: the uninterrupted reference run into $tmp/whole, then a run of the same
# input stopped by SIGNAL after a checkpoint into $tmp/parts (up to three tries when a run finishes
# before the signal lands). Sets $status to the stopped run's exit status (or "finished").
interrupted_pair() {
  restart_input "$tmp/input.json"
  "$matpoint" run "$tmp/input.json" --quiet --threads 1 --out "$tmp/whole" >/dev/null || fail "uninterrupted run failed"
  local attempt
  for attempt in 1 2 3; do
    rm -rf "$tmp/parts"
    status=$(run_until_checkpoint "$1" "$tmp/input.json" "$tmp/parts")
    [[ $status == finished ]] || break
  done
}
