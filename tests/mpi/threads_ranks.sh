#!/usr/bin/env bash
# Issue 23 item 3, threads x ranks: OpenMP inside each rank. `mpirun -n 2 matpoint run --threads 2`
# of two elastic disks (examples/two-disks with h = 0.01: 10 048 particles, about 5000 per rank, so
# every rank's scatter, gathers and particle loops really run on 2 threads: more than
# kParallelMinimum = 4096) gives the serial one-thread run's particles bit for bit at every output,
# through the impact (the scatter's order is the brick colouring's, the same for any number of
# threads and ranks: docs/scale-out.md §6), and its summary reports 2 ranks of 2 threads. A second,
# short run shows that OMP_NUM_THREADS is honoured per rank when --threads is not given.
# Expected values: the serial run (bitwise), and the thread and rank counts the commands ask for.
source "$(dirname "${BASH_SOURCE[0]}")/../cli/common.bash"
mpiexec=$3
# mpirun binds each rank to one core by default (OpenMPI: with 2 ranks), which would put both of a
# rank's threads on one core (summary.json cpus_per_rank, and a warning); results are the same either way.
export OMPI_MCA_hwloc_base_binding_policy=none

"$python" - "$tmp" <<'PY'
import json, os, sys
tmp = sys.argv[1]
def disks(end_time, every):
    return {
        "title": "two elastic disks, h = 0.01 (threads x ranks)",
        "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.01},
        "materials": [{"name": "elastic", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
        "bodies": [
            {"name": "lower-left", "material": "elastic",
             "shape": {"type": "disk", "center": [0.25, 0.25], "radius": 0.2},
             "particles_per_cell": 2, "velocity": [0.1, 0.1]},
            {"name": "upper-right", "material": "elastic",
             "shape": {"type": "disk", "center": [0.75, 0.75], "radius": 0.2},
             "particles_per_cell": 2, "velocity": [-0.1, -0.1]}],
        "solver": {"scheme": "musl", "transfer": "flip", "basis": "bspline2", "dt": 0.001,
                   "end_time": end_time},
        "output": {"every_time": every, "plots": False},
    }
# The disks meet at t = 1.08 (gap 0.5 sqrt 2 - 0.4 = 0.307 closing at 0.2 sqrt 2 = 0.283 per unit
# time); t = 1.5 is in the impact, where another summation order shows (docs/scale-out.md §6).
json.dump(disks(1.5, 0.5), open(os.path.join(tmp, "input.json"), "w"))
json.dump(disks(0.02, 0.01), open(os.path.join(tmp, "short.json"), "w"))
PY

"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/serial" --threads 1 >/dev/null || fail "the serial run failed"
"$mpiexec" -n 2 "$matpoint" run "$tmp/input.json" --quiet --out "$tmp/ranks" --threads 2 >"$tmp/mpi.log" 2>&1 ||
  fail "mpirun -n 2 ... --threads 2 failed: $(tail -20 "$tmp/mpi.log")"
# OMP_NUM_THREADS (no --threads): each rank's OpenMP takes it (the tests' environment sets 1).
OMP_NUM_THREADS=2 "$mpiexec" -n 2 "$matpoint" run "$tmp/short.json" --quiet --out "$tmp/omp" >"$tmp/omp.log" 2>&1 ||
  fail "OMP_NUM_THREADS=2 mpirun -n 2 failed: $(tail -20 "$tmp/omp.log")"

"$python" - "$tmp" <<'PY'
import glob, json, os, re, sys
import meshio
import numpy as np
tmp = sys.argv[1]
serial, ranks = os.path.join(tmp, "serial"), os.path.join(tmp, "ranks")

def parallel(folder):
    s = json.load(open(os.path.join(folder, "summary.json")))
    assert s["status"] == "ok", s["status"]
    return s, s.get("parallel")

s, p = parallel(ranks)
assert s["particles"] == 10048, s["particles"]
assert p is not None, "a decomposed run's summary has a 'parallel' object"
assert p["ranks"] == 2, p["ranks"]
assert p["threads_per_rank"] == {"min": 2, "max": 2}, p["threads_per_rank"]
assert s["threads"] == 2, s["threads"]
assert p["particles_per_rank"]["min"] + p["particles_per_rank"]["max"] == 10048, p["particles_per_rank"]
# The disks' particles cross the cut (the upper disk moves down into the lower rank's slab).
assert p["migrated_particles_per_step"]["sum"] > 0, p
assert p["halo_bytes_per_step"]["sum"] > 0 and p["halo_messages_per_step"]["sum"] > 0, p
_, q = parallel(os.path.join(tmp, "omp"))
assert q["threads_per_rank"] == {"min": 2, "max": 2}, ("OMP_NUM_THREADS=2 per rank", q["threads_per_rank"])
_, none = parallel(serial)
assert none is None, "a serial run has no 'parallel' object"

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

outputs = sorted(glob.glob(os.path.join(serial, "particles_*.vtu")))
assert len(outputs) == 4, outputs  # t = 0, 0.5, 1.0, 1.5
for vtu in outputs:
    number = re.search(r"particles_(\d+)\.vtu", vtu).group(1)
    pvtu = open(os.path.join(ranks, f"particles_{number}.pvtu")).read()
    pieces = re.findall(r'<Piece Source="([^"]+)"', pvtu)
    assert len(pieces) == 2, pieces
    a = particles([vtu])
    b = particles([os.path.join(ranks, piece) for piece in pieces])
    assert np.array_equal(a["id"], b["id"]), "every particle exactly once"
    for name in ("x", "velocity", "stress"):
        assert np.array_equal(a[name], b[name]), (number, name, np.abs(a[name] - b[name]).max())
print(f"PASS: 2 ranks x 2 threads equal the serial 1-thread run bit for bit at {len(outputs)} outputs "
      f"({p['particles_per_rank']['min']}-{p['particles_per_rank']['max']} particles per rank, "
      f"{p['migrated_particles_per_step']['sum']:.2f} migrating per step); OMP_NUM_THREADS=2 gives 2 per rank")
PY
