#!/usr/bin/env bash
# Issue 23, per-rank checkpoints through the command line (docs/scale-out.md §9): examples/two-disks
# (416 particles, MUSL, FLIP, quadratic B-splines) to t = 0.6 with a checkpoint every 50 steps.
# `mpirun -n 4 matpoint run` stopped at step 253 writes one piece per rank and the manifest
# checkpoint.h5 (the pieces of the last two checkpoints stay); `--restart` continues it on 4 ranks,
# on 2 (the particles redistributed) and without mpirun, and each last output equals the serial
# uninterrupted run's bit for bit (x, velocity, stress by id; a decomposed run equals the serial one,
# docs/scale-out.md §6), its history to 1e-12 of each column's largest value (the ranks' sums are
# added in another association than the serial loop's: round-off only).
source "$(dirname "${BASH_SOURCE[0]}")/../cli/common.bash"
root=$2
mpiexec=$3
sed -e 's/"end_time": 3.0/"end_time": 0.6/' \
  -e 's/"output": { "every_time": 0.05 }/"output": { "every_time": 0.05, "plots": false, "checkpoint": { "every_steps": 50 } }/' \
  "$root/examples/two-disks/input.json" >"$tmp/full.json"
sed 's/"dt": 0.001,/"dt": 0.001, "max_steps": 253,/' "$tmp/full.json" >"$tmp/stop.json"
grep -q '"checkpoint"' "$tmp/full.json" && grep -q '"max_steps": 253' "$tmp/stop.json" || fail "could not edit the example"

"$matpoint" run "$tmp/full.json" --quiet --out "$tmp/serial" --threads 1 >/dev/null || fail "the serial run failed"
"$mpiexec" -n 4 "$matpoint" run "$tmp/stop.json" --quiet --out "$tmp/ranks" --threads 1 >"$tmp/stop.log" 2>&1 ||
  fail "mpirun -n 4 (to step 253) failed: $(tail -20 "$tmp/stop.log")"
pieces=$(ls "$tmp/ranks" | grep -c '^checkpoint\.s.*\.h5$' || true)
[[ $pieces == 8 ]] || fail "expected the pieces of the last two checkpoints (2 x 4), found $pieces: $(ls "$tmp/ranks")"
[[ -f "$tmp/ranks/checkpoint.s00000253.r0003.h5" ]] || fail "no piece of rank 3 at step 253: $(ls "$tmp/ranks")"

cp -r "$tmp/ranks" "$tmp/ranks2"
cp -r "$tmp/ranks" "$tmp/ranks1"
"$mpiexec" -n 4 "$matpoint" run "$tmp/full.json" --quiet --restart "$tmp/ranks/checkpoint.h5" --threads 1 \
  >"$tmp/rest.log" 2>&1 || fail "mpirun -n 4 --restart failed: $(tail -20 "$tmp/rest.log")"
"$mpiexec" -n 2 "$matpoint" run "$tmp/full.json" --quiet --restart "$tmp/ranks2/checkpoint.h5" --threads 1 \
  >"$tmp/rest2.log" 2>&1 || fail "mpirun -n 2 --restart (of 4 ranks' checkpoint) failed: $(tail -20 "$tmp/rest2.log")"
"$matpoint" run "$tmp/full.json" --quiet --restart "$tmp/ranks1/checkpoint.h5" --threads 1 \
  >"$tmp/rest1.log" 2>&1 || fail "matpoint run --restart (of 4 ranks' checkpoint) failed: $(tail -20 "$tmp/rest1.log")"

"$python" - "$tmp/serial" "$tmp/ranks" "$tmp/ranks2" "$tmp/ranks1" <<'PY'
import csv, glob, json, os, re, sys
import meshio
import numpy as np
serial = sys.argv[1]

def particles(files):
    fields = {}
    for f in files:
        if b'NumberOfPoints="0"' in open(f, "rb").read(4096):
            continue  # a rank without particles (meshio does not read an empty piece)
        m = meshio.read(f)
        data = {"x": m.points[:, :2], **{k: np.asarray(v) for k, v in m.point_data.items()}}
        for k, v in data.items():
            fields.setdefault(k, []).append(v)
    fields = {k: np.concatenate(v) for k, v in fields.items()}
    order = np.argsort(fields["id"])
    return {k: v[order] for k, v in fields.items()}

last = sorted(glob.glob(os.path.join(serial, "particles_*.vtu")))[-1]
number = re.search(r"particles_(\d+)\.vtu", last).group(1)
a = particles([last])

def history(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "history.csv"))))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
hs = history(serial)
body_momentum = max(np.abs(hs[f"body{b}_momentum_{a}"]).max() for b in (0, 1) for a in "xy")
report = []
for ranks, count in zip(sys.argv[2:], (4, 2, 1)):
    summary = json.load(open(os.path.join(ranks, "summary.json")))
    assert summary["status"] == "ok" and summary["restarted_at_step"] == 253, (ranks, summary)
    assert summary["steps"] == json.load(open(os.path.join(serial, "summary.json")))["steps"]
    assert all(c["pass"] for c in summary["checks"]), summary["checks"]
    pvtu = os.path.join(ranks, f"particles_{number}.pvtu")
    if count > 1:
        pieces = re.findall(r'<Piece Source="([^"]+)"', open(pvtu).read())
        assert len(pieces) == count, pieces
        b = particles([os.path.join(ranks, p) for p in pieces])
    else:
        assert not os.path.exists(pvtu), pvtu
        b = particles([os.path.join(ranks, f"particles_{number}.vtu")])
    assert np.array_equal(a["id"], b["id"]), "every particle exactly once"
    for name in ("x", "velocity", "stress"):
        assert np.array_equal(a[name], b[name]), (ranks, name, np.abs(a[name] - b[name]).max())
    hr = history(ranks)
    assert len(hs["time"]) == len(hr["time"]), (len(hs["time"]), len(hr["time"]))
    worst = 0.0
    for column in ("time", "kinetic_energy", "strain_energy", "momentum_x", "momentum_y",
                   "body0_momentum_x", "body1_momentum_y"):
        scale = body_momentum if column.startswith("momentum") else max(np.abs(hs[column]).max(), 1e-300)
        worst = max(worst, np.abs(hs[column] - hr[column]).max() / scale)
        assert np.abs(hs[column] - hr[column]).max() <= 1e-12 * scale, (ranks, column)
    report.append(f"{count} rank(s): history within {worst:.1e}")
print(f"PASS: 4 ranks' checkpoint at step 253 continued on 4, 2 and 1 rank(s): {len(a['id'])} particles "
      f"at output {number} equal the serial run's bit for bit; " + "; ".join(report))
PY
