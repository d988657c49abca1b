#!/usr/bin/env bash
# Issue 23, verification 1 through the command line: examples/two-disks (416 particles, 3000 steps,
# MUSL, FLIP, quadratic B-splines) run by `mpirun -n 2 matpoint run` gives the serial run's
# particles bit for bit (every output piece, gathered by id: x, velocity, stress) and its history
# (energies, momenta) to 1e-12 of each column's largest value (a body's momentum for the total) (the ranks' sums are added in another
# association than the serial loop's: round-off only), passes the example's checks, and writes one
# .pvtu per output listing both ranks' pieces.
source "$(dirname "${BASH_SOURCE[0]}")/../cli/common.bash"
root=$2
mpiexec=$3
example="$root/examples/two-disks/input.json"

"$matpoint" run "$example" --quiet --out "$tmp/serial" --threads 1 >/dev/null || fail "the serial run failed"
"$mpiexec" -n 2 "$matpoint" run "$example" --quiet --out "$tmp/ranks" --threads 1 >"$tmp/mpi.log" 2>&1 ||
  fail "mpirun -n 2 failed: $(tail -20 "$tmp/mpi.log")"

"$python" - "$tmp/serial" "$tmp/ranks" <<'PY'
import csv, glob, json, os, re, sys
import meshio
import numpy as np
serial, ranks = sys.argv[1:]
for folder in (serial, ranks):
    summary = json.load(open(os.path.join(folder, "summary.json")))
    assert all(c["pass"] for c in summary["checks"]), summary["checks"]
    assert summary["particles"] == 416, summary["particles"]

def particles(files):
    fields = {}
    for f in files:
        m = meshio.read(f)
        data = {"x": m.points[:, :2], **{k: np.asarray(v) for k, v in m.point_data.items()}}
        for k, v in data.items():
            fields.setdefault(k, []).append(v)
    fields = {k: np.concatenate(v) for k, v in fields.items()}
    order = np.argsort(fields["id"])
    return {k: v[order] for k, v in fields.items()}

last = sorted(glob.glob(os.path.join(serial, "particles_*.vtu")))[-1]
number = re.search(r"particles_(\d+)\.vtu", last).group(1)
pvtu = open(os.path.join(ranks, f"particles_{number}.pvtu")).read()
pieces = re.findall(r'<Piece Source="([^"]+)"', pvtu)
assert len(pieces) == 2, pieces
a = particles([last])
b = particles([os.path.join(ranks, p) for p in pieces])
assert np.array_equal(a["id"], b["id"]), "every particle exactly once"
for name in ("x", "velocity", "stress"):
    assert np.array_equal(a[name], b[name]), (name, np.abs(a[name] - b[name]).max())

def history(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "history.csv"))))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
hs, hr = history(serial), history(ranks)
worst = 0.0
# The total momentum of the two disks is zero up to round-off (they move in opposite directions):
# its scale is a body's momentum.
body_momentum = max(np.abs(hs[f"body{b}_momentum_{a}"]).max() for b in (0, 1) for a in "xy")
for column in ("time", "kinetic_energy", "strain_energy", "momentum_x", "momentum_y",
               "body0_momentum_x", "body1_momentum_y"):
    scale = body_momentum if column.startswith("momentum") else max(np.abs(hs[column]).max(), 1e-300)
    worst = max(worst, np.abs(hs[column] - hr[column]).max() / scale)
    assert np.abs(hs[column] - hr[column]).max() <= 1e-12 * scale, column
print(f"PASS: {len(a['id'])} particles at output {number} equal bit for bit on 2 ranks; "
      f"history within {worst:.1e} of each column's largest value")
PY
