#!/usr/bin/env bash
# A small valid 2-D run writes whole, readable outputs: VTU files listed in results.pvd, history.csv
# with one row per VTU file, summary.json, plots/energy.png, and no leftover *.partial file.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

cat >"$tmp/input.json" <<'JSON'
{ "title": "cli output test",
  "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.05},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.5, 0.5], "radius": 0.2},
              "velocity": [0.1, 0]}],
  "solver": {"dt": 0.001, "end_time": 0.05}, "output": {"every_steps": 10} }
JSON

status=0
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/out" >"$tmp/run.out" 2>"$tmp/run.err" || status=$?
[[ $status -eq 0 ]] || fail "matpoint run exited $status:"$'\n'"$(cat "$tmp/run.err")"

leftovers=$(find "$tmp/out" -name '*.partial*')
[[ -z "$leftovers" ]] || fail "temporary files left behind: $leftovers"

"$python" - "$tmp/out" <<'PY'
import csv, json, os, sys
import xml.etree.ElementTree as ET
import meshio
import numpy as np

out = sys.argv[1]
def fail(message):
    sys.exit(f"FAIL: {message}")

summary = json.load(open(os.path.join(out, "summary.json")))
if summary["status"] != "ok" or summary["exit_code"] != 0:
    fail(f"summary status {summary['status']!r}, exit_code {summary['exit_code']}")
n = summary["particles"]
if n <= 0:
    fail(f"summary.json particles = {n}")

files = [d.get("file") for d in ET.parse(os.path.join(out, "results.pvd")).getroot().iter("DataSet")]
if len(files) < 2:
    fail(f"results.pvd lists {len(files)} files")
for name in files:
    mesh = meshio.read(os.path.join(out, name))
    if len(mesh.points) != n:
        fail(f"{name}: {len(mesh.points)} points, summary.json says {n} particles")
    if not np.all(np.isfinite(mesh.points)):
        fail(f"{name}: non-finite positions")
    for array in ("velocity", "stress", "mass", "id"):
        if array not in mesh.point_data:
            fail(f"{name}: no point array {array!r} (has {sorted(mesh.point_data)})")
        if len(mesh.point_data[array]) != n:
            fail(f"{name}: array {array!r} has {len(mesh.point_data[array])} entries")

with open(os.path.join(out, "history.csv"), newline="") as f:
    rows = list(csv.reader(f))
header, data = rows[0], rows[1:]
expected = ["time", "step", "kinetic_energy", "strain_energy", "total_energy"]
if header[:5] != expected:
    fail(f"history.csv starts with {header[:5]}, expected {expected}")
if len(data) != len(files):
    fail(f"history.csv has {len(data)} rows, results.pvd lists {len(files)} files")

with open(os.path.join(out, "plots", "energy.png"), "rb") as f:
    if f.read(4) != b"\x89PNG":
        fail("plots/energy.png is not a PNG")
print(f"{len(files)} VTU files of {n} particles, {len(data)} history rows, energy.png: all consistent")
PY
echo "PASS: outputs written and readable"
