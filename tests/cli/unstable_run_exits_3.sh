#!/usr/bin/env bash
# A time step 20 times too large makes the run blow up: exit 3, a message naming the step, time and
# particle, summary.json with status numerical_failure, and the last listed VTU file still whole
# and finite.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

# c = sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))) ~ 37 m/s with E = 1e6, so a 0.05 m cell is crossed
# in ~ 1.3e-3 s; dt = 0.01 is far beyond the stable step.
cat >"$tmp/input.json" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.05},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e6, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.5, 0.5], "radius": 0.2},
              "velocity": [0.1, 0]}],
  "solver": {"dt": 0.01, "end_time": 1}, "output": {"every_steps": 1, "plots": false} }
JSON

status=0
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/out" >"$tmp/run.out" 2>"$tmp/run.err" || status=$?
[[ $status -eq 3 ]] || fail "matpoint run exited $status, expected 3; stderr:"$'\n'"$(cat "$tmp/run.err")"
for word in step time particle; do
  grep -qi "$word" "$tmp/run.err" || fail "stderr does not name the $word:"$'\n'"$(cat "$tmp/run.err")"
done

"$python" - "$tmp/out" <<'PY'
import json, os, sys
import xml.etree.ElementTree as ET
import meshio
import numpy as np

out = sys.argv[1]
def fail(message):
    sys.exit(f"FAIL: {message}")

summary = json.load(open(os.path.join(out, "summary.json")))
if summary["status"] != "numerical_failure" or summary["exit_code"] != 3:
    fail(f"summary status {summary['status']!r}, exit_code {summary['exit_code']}")
files = [d.get("file") for d in ET.parse(os.path.join(out, "results.pvd")).getroot().iter("DataSet")]
if not files:
    fail("results.pvd lists no file")
mesh = meshio.read(os.path.join(out, files[-1]))
if len(mesh.points) != summary["particles"]:
    fail(f"{files[-1]}: {len(mesh.points)} points, expected {summary['particles']}")
if not np.all(np.isfinite(mesh.points)):
    fail(f"{files[-1]}: the last good output has non-finite positions")
print(f"failed at step {summary['steps']}: {summary['message']}")
PY
echo "PASS: unstable run stopped with exit 3 and kept the last good output"
