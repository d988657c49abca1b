#!/usr/bin/env bash
# Load balancing's benefit (issue 23; docs/scale-out.md §10): the cohesive soil column of
# examples/soil-column-collapse on 2 MPI ranks, with re-partitioning off and with the default
# solver.rebalance (imbalance 1.15, min_steps 100). The slabs are cut along y; the column (2 m
# high) slumps to about 1.5 m, so the upper rank loses particles to the lower one as it collapses.
# Fine grid h = 0.025 m (12 800 particles, 11 brick layers along y), to t = 1 s, no particle
# output. Prints per run: re-partitions, the final particles per rank (min / max, imbalance), the
# slowest rank's step wall time, and the rate. Best of REPEAT interleaved runs (the machine may be
# shared; run it idle). Usage: bench/rebalance_column.sh [MPI_BUILD_DIR] [REPEAT]
set -euo pipefail
build=${1:-build-mpi}
repeat=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work" <<'PY'
import json, re, sys
work = sys.argv[1]
text = open("examples/soil-column-collapse/input.json").read()
spec = json.loads(re.sub(r"^\s*//.*$", "", text, flags=re.M))
spec["grid"]["cell_size"] = 0.025
spec["solver"]["end_time"] = 1.0
spec["output"] = {"every_time": 1.0, "particles": False, "plots": False}
spec["checks"] = []
spec["solver"]["rebalance"] = "off"
json.dump(spec, open(f"{work}/off.json", "w"))
spec["solver"].pop("rebalance")
json.dump(spec, open(f"{work}/default.json", "w"))
PY
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
for k in $(seq "$repeat"); do
  for mode in off default; do
    mpirun -n 2 --oversubscribe --bind-to none "$build/matpoint" run "$work/$mode.json" \
      --out "$work/$mode.$k" --threads 1 --overwrite > /dev/null
  done
done
python3 - "$work" "$repeat" <<'PY'
import json, sys
work, repeat = sys.argv[1], int(sys.argv[2])
print("| solver.rebalance | re-partitions | particles per rank at the end (min / max) | imbalance at the end | step wall s, slowest rank (best) | M particle-steps/s (best; all) | load |")
print("|---|---|---|---|---|---|---|")
for mode in ("off", "default"):
    runs = [json.load(open(f"{work}/{mode}.{k}/summary.json")) for k in range(1, repeat + 1)]
    par = [r["parallel"] for r in runs]
    best = min(range(repeat), key=lambda k: par[k]["step_wall_seconds"]["max"])
    p = par[best]["particles_per_rank"]
    rates = [r["particle_steps_per_second"] / 1e6 for r in runs]
    load = open("/proc/loadavg").read().split()[0]
    print(f"| {mode} | {par[best]['repartitions']} | {p['min']} / {p['max']} | {p['imbalance']:.3f} | "
          f"{par[best]['step_wall_seconds']['max']:.2f} | {max(rates):.2f} ({' / '.join(f'{x:.2f}' for x in rates)}) | {load} |")
PY
