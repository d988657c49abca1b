#!/usr/bin/env python3
"""Strong and weak scaling of bench-2d and bench-3d on 1 -> 2 ranks and 1 -> 2 threads, and a model
calibrated by them that predicts parallel efficiency at 64 and 1024 ranks (issue 23 item 4).

    python3 bench/scaling.py [build-mpi/matpoint] [--repeats 3] [--steps 20] [--out bench/scaling.md]

Runs every point `--repeats` times, interleaved (all points once, then again), with the machine's
load average before each run; writes the tables, the exchange counters of summary.json's
`parallel` object (docs/output.md) and the model to bench/scaling.md. Python 3 standard library
only; needs an MPI build of matpoint (-DMATPOINT_PETSC=ON) and mpirun. About 5 minutes on a
2-core machine.
"""
import argparse
import datetime
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# --------------------------------------------------------------------------------------------
# Inputs


def read_input(path):
    """An example's input.json (JSON with // comment lines)."""
    text = "\n".join(line for line in open(path) if not line.lstrip().startswith("//"))
    return json.loads(text)


WIDE = 8  # the node term's calibration: the grid this many times as long along x, same body


def variant(spec, steps, longer=False, wider=False):
    """bench-2d/3d with max_steps = steps; `longer`: the body (and grid) twice as long along the cut
    axis (the last: y in 2-D, z in 3-D), twice the particles; `wider`: the grid WIDE times as long
    along x with the body unchanged (the node term's calibration)."""
    s = json.loads(json.dumps(spec))
    s["solver"]["max_steps"] = steps
    s["output"] = {"particles": False, "plots": False}
    dim = s["grid"]["dim"]
    box = s["bodies"][0]["shape"]
    if longer:
        a = dim - 1
        length = box["max"][a] - box["min"][a]
        box["max"][a] += length
        s["grid"]["max"][a] += length
    if wider:
        s["grid"]["max"][0] += (WIDE - 1) * (s["grid"]["max"][0] - s["grid"]["min"][0])
    return s


def cells(spec):
    g = spec["grid"]
    return [round((hi - lo) / g["cell_size"]) for lo, hi in zip(g["min"], g["max"])]


def nodes(spec):
    return math.prod(c + 1 for c in cells(spec))


# --------------------------------------------------------------------------------------------
# Runs


def load_average():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def run_point(args, point, work, repeat):
    """One run of a point; returns its summary.json plus the load before and after."""
    out = os.path.join(work, f"{point['name']}.{repeat}")
    cmd = [args.matpoint, "run", point["input"], "--out", out, "--quiet", "--overwrite",
           "--threads", str(point["threads"])]
    if point["ranks"] > 1:
        extra = point.get("mpirun_args", args.mpirun_args)
        cmd = [args.mpirun, "-n", str(point["ranks"]), "--oversubscribe"] + extra.split() + cmd
    env = dict(os.environ)
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.pop("OMP_NUM_THREADS", None)  # --threads decides
    load_before = load_average()
    t0 = time.monotonic()
    done = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - t0
    if done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): {' '.join(cmd)}\n{done.stdout[-3000:]}")
    summary = json.load(open(os.path.join(out, "summary.json")))
    return {"summary": summary, "load_before": load_before, "load_after": load_average(), "process_wall": wall}


def points(args, work):
    """The measured points: case, ranks, threads, input variant."""
    out = []
    for case in ("bench-2d", "bench-3d"):
        base = read_input(os.path.join(ROOT, "examples", case, "input.json"))
        specs = {"": variant(base, args.steps), "long": variant(base, args.steps, longer=True),
                 "wide": variant(base, args.steps, wider=True)}
        files = {}
        for key, spec in specs.items():
            files[key] = os.path.join(work, f"{case}{'-' + key if key else ''}.json")
            with open(files[key], "w") as f:
                json.dump(spec, f, indent=1)
        d = case[-2:]
        table = [(f"{d} 1x1", 1, 1, "", "strong"), (f"{d} 2x1", 2, 1, "", "strong"),
                 (f"{d} 1x2", 1, 2, "", "strong"), (f"{d} 2x2", 2, 2, "", "strong"),
                 (f"{d} weak 2x1", 2, 1, "long", "weak"), (f"{d} wide 1x1", 1, 1, "wide", "calibration")]
        if d == "2d":  # mpirun's default binding (each rank on one core) with 2 threads per rank
            table.insert(4, (f"{d} 2x2 bound", 2, 2, "", "binding"))
        for name, ranks, threads, key, kind in table:
            point = {"name": name.replace(" ", "_"), "label": name, "case": case, "dim": int(d[0]),
                     "ranks": ranks, "threads": threads, "kind": kind, "input": files[key], "spec": specs[key]}
            if kind == "binding":
                point["mpirun_args"] = "--bind-to core"
            out.append(point)
    return out


# --------------------------------------------------------------------------------------------
# Reading the runs


def wall_per_step(summary):
    """Wall seconds per step of the slowest rank (the process's for a one-rank run)."""
    p = summary.get("parallel")
    return (p["step_wall_seconds"]["max"] if p else summary["step_wall_seconds"]) / summary["steps"]


def cpu_per_step(summary):
    """CPU seconds per step of the busiest rank: what the step takes on a core of its own."""
    p = summary.get("parallel")
    return (p["step_cpu_seconds"]["max"] if p else summary["step_cpu_seconds"]) / summary["steps"]


def median_run(runs):
    """The run with the median step time (its counters are reported)."""
    ordered = sorted(runs, key=lambda r: wall_per_step(r["summary"]))
    return ordered[len(ordered) // 2]


def mean_local(p, what):
    """A rank's own work per step in the hand-off or the migration (its seconds less the time inside
    the exchange), averaged over the ranks."""
    return (p[f"{what}_seconds"]["sum"] - p[f"{what}_wait_seconds"]["sum"]) / p["ranks"] / p["steps"]


# --------------------------------------------------------------------------------------------
# The model

# Cluster interconnect assumed for the predictions (an InfiniBand HDR / Slingshot class network).
CLUSTER_LATENCY = 1.5e-6     # s per message (1-2 us)
CLUSTER_BANDWIDTH = 12.5e9   # B/s per rank (10-25 GB/s)
# This machine's plain MPI exchange, docs/scale-out.md §13 (p10 fit, shared memory, OpenMPI 4.1.4).
LOCAL_LATENCY = 1.0e-6
LOCAL_BANDWIDTH = 1.9e9
# Bytes a migrating 3-D particle carries: every array of for_each_array (docs/scale-out.md §5: 368 B
# before the material state) and its 8-byte sort key; used where the measured runs moved none.
BYTES_PER_PARTICLE_3D = 384


def calibrate(results, dim):
    """c_p (CPU s per particle-step, node work excluded) and c_n (CPU s per node-step) from the
    1-rank runs of bench-dD and its wide-grid variant (median CPU time per step)."""
    one, wide = results[f"{dim}d_1x1"], results[f"{dim}d_wide_1x1"]
    t1, tw = one["cpu"], wide["cpu"]
    n1, nw = nodes(one["point"]["spec"]), nodes(wide["point"]["spec"])
    particles = one["summary"]["particles"]
    c_n = max(0.0, (tw - t1) / (nw - n1))
    c_p = (t1 - c_n * n1) / particles
    return {"c_p": c_p, "c_n": c_n, "nodes": n1, "wide_nodes": nw, "particles": particles, "t1": t1, "tw": tw}


def exchange_costs(run):
    """From a 2-rank run's counters: c_m, the migration's own work per particle-step (the owner of
    every particle's cell, the stable compaction of every array), and c_h, the hand-off's own work
    per byte sent (packing and unpacking): their CPU time outside the exchange, averaged over the
    ranks."""
    p = run["summary"]["parallel"]
    steps, ranks = p["steps"], p["ranks"]
    mean_particles = run["summary"]["particles"] / ranks
    c_m = p["migration_own_cpu_seconds"]["sum"] / ranks / steps / mean_particles
    c_h = p["halo_own_cpu_seconds"]["sum"] / ranks / steps / max(p["halo_bytes_per_step"]["sum"] / ranks, 1.0)
    return {"c_m": c_m, "c_h": c_h}


def model_terms(n, grid_nodes, cal, costs, halo_messages, halo_bytes, migration_messages, migration_bytes,
                collectives, P, latency, bandwidth):
    """The model's terms, seconds per step of a rank: particles, grid, the hand-off's and the
    migration's own work ("own"), and the wire of the halo, the migration and the collectives."""
    return {
        "particles": n * cal["c_p"],
        "grid": grid_nodes * cal["c_n"],
        "own": halo_bytes * costs["c_h"] + n * costs["c_m"],
        "halo": halo_messages * latency + halo_bytes / bandwidth,
        "migration": migration_messages * latency + migration_bytes / bandwidth,
        "collectives": collectives * (2 * math.log2(P) * latency + P * 8 / bandwidth),
    }


def predict_measured(run, cal, costs):
    """The model's CPU time per step for a measured 2-rank run (each rank loops over its window of the
    grid: the largest window counted by the run, or the whole grid for a build before the window)."""
    p = run["summary"]["parallel"]
    stored = p.get("stored_nodes_per_rank", {}).get("max", nodes(run["point"]["spec"]))
    terms = model_terms(p["particles_per_rank"]["max"], stored, cal, costs,
                        p["halo_messages_per_step"]["max"], p["halo_bytes_per_step"]["max"],
                        p["migration_messages_per_step"]["max"], p["migration_bytes_per_step"]["max"],
                        p["collectives_per_step"]["max"] + 1, p["ranks"], LOCAL_LATENCY, LOCAL_BANDWIDTH)
    return sum(terms.values()), terms


MARGIN = 5  # bench-3d's grid reaches 5 cells beyond the body on every side


def scaled_up(P, per_rank, cal, costs, counters, geometry, windowed):
    """Step time per rank and weak-scaling efficiency of bench-3d scaled up to P ranks with
    `per_rank` particles each (8 per cell). geometry "rod": bench-3d's 40 x 40-cell cross-section,
    P slabs along z; "cube": RCB boxes of (per_rank / 8)^(1/3) cells a side, 26 neighbours."""
    if geometry == "rod":
        cross = 40
        thick = per_rank / (8 * cross * cross)  # cells along z per rank
        plane = (cross + 2 * MARGIN + 1) ** 2   # grid nodes of a cut plane
        faces, face_nodes, neighbours, face_cells = 2, plane, 2, cross * cross
        window = plane * (thick + 4)  # owned + ghost node layers (bspline2: 1 below, 2 above)
        whole = plane * (thick * P + 2 * MARGIN + 1)
        alone = plane * (thick + 2 * MARGIN + 1)
        layers = thick / 8
    else:
        side = (per_rank / 8) ** (1 / 3)
        faces, face_nodes, neighbours, face_cells = 6, (side + 4) ** 2, 26, side * side
        window = (side + 4) ** 3
        whole = (side * P ** (1 / 3) + 2 * MARGIN + 1) ** 3
        alone = (side + 2 * MARGIN + 1) ** 3
        layers = side / 8
    grid_nodes = window if windowed else whole
    halo_bytes = faces * face_nodes * counters["halo_bytes_per_plane_node"]
    migrated = faces * face_cells * counters["migrated_per_face_cell"]
    terms = model_terms(per_rank, grid_nodes, cal, costs,
                        neighbours * counters["halo_messages_per_neighbour"], halo_bytes,
                        neighbours, migrated * counters["bytes_per_particle"],
                        counters["collectives_per_step"], P, CLUSTER_LATENCY, CLUSTER_BANDWIDTH)
    t = sum(terms.values())
    t1 = per_rank * cal["c_p"] + alone * cal["c_n"]  # one rank alone with the same particles
    return {"t": t, "t1": t1, "efficiency": t1 / t, **terms, "halo_bytes": halo_bytes, "migrated": migrated,
            "layers_per_rank": layers, "grid_nodes": grid_nodes,
            "grid_gib": grid_nodes * 8 * counters["doubles_per_node"] / 2 ** 30}


# --------------------------------------------------------------------------------------------
# The report


def fmt(x, digits=3):
    if x == 0:
        return "0"
    if abs(x) >= 1e4 or abs(x) < 1e-3:
        return f"{x:.{digits - 1}e}"
    return f"{x:.{digits}g}"


def rates(runs):
    return " / ".join(f"{x['summary']['particle_steps_per_second'] / 1e6:.2f}" for x in runs)


def load_list(runs):
    return " / ".join(f"{x['load_before']:.1f}" for x in runs)


def machine():
    model = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True).stdout.strip()
    mpirun = subprocess.run(["mpirun", "--version"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True).stdout.splitlines()
    return model, os.cpu_count(), commit, (mpirun[0] if mpirun else "")


STATED_ERROR = 0.15


def report(args, pts, runs, elapsed, finished=None):
    results = {}
    for pt in pts:
        rs = runs[pt["name"]]
        results[pt["name"]] = {
            "point": pt, "runs": rs, "summary": median_run(rs)["summary"],
            "wall": statistics.median(wall_per_step(r["summary"]) for r in rs),
            "cpu": statistics.median(cpu_per_step(r["summary"]) for r in rs),
            "rate": statistics.median(r["summary"]["particle_steps_per_second"] for r in rs)}
    model, cores, commit, mpi = machine()
    loads = [r["load_before"] for rs in runs.values() for r in rs]
    loaded = max(loads) > 1.5
    L = []
    w = L.append
    w("# Scaling: 1 -> 2 ranks and 1 -> 2 threads, and a model for 64 and 1024 ranks")
    w("")
    w(f"Generated by `python3 bench/scaling.py {args.matpoint}` (issue 23 item 4; rerun the script "
      "rather than editing this file). "
      f"{finished or datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}, commit {commit}, "
      f"{model}, {cores} cores, {mpi}; {args.steps} steps per run, {args.repeats} runs per point, "
      f"interleaved (every point once, then again); ranks started with `mpirun -n 2 --oversubscribe "
      f"{args.mpirun_args}`; {elapsed / 60:.1f} minutes of runs.")
    w("")
    w(f"**Machine load:** the 1-minute load average before the runs was {min(loads):.1f} to "
      f"{max(loads):.1f} (median {statistics.median(loads):.1f}) on {cores} cores" +
      (": other processes (builds and tests) shared the cores, so these are numbers from a **loaded "
       "machine**: the wall-time rates below are what our processes got of the cores, not what the "
       "code can do, and 2 processes rarely had both cores. The model is therefore calibrated and "
       "checked in CPU time (a rank's CPU seconds in the steps: the time of the step on a core of its "
       "own), which the other processes disturb much less. Rerun on an idle machine for clean rates."
       if loaded else " (an idle machine)."))
    w("")
    w("Rate: summary.json's `particle_steps_per_second` (particles x steps / wall time of the steps, "
      "set-up excluded; on several ranks rank 0's wall time); per core = speed-up / (ranks x threads). "
      "Wall ms: the slowest rank's `parallel.step_wall_seconds.max` / steps; CPU ms: the busiest "
      "rank's CPU time per step (`step_cpu_seconds`, all its threads).")
    w("")
    w("## Strong scaling (the same problem on more cores)")
    w("")
    w("| case | ranks x threads | particles | M particle-steps/s (median; all runs) | speed-up | per core | wall ms per step | CPU ms per step | load before each run |")
    w("|---|---|---|---|---|---|---|---|---|")
    for d in (2, 3):
        base = results[f"{d}d_1x1"]
        for key in ("1x1", "2x1", "1x2", "2x2", "2x2_bound"):
            if f"{d}d_{key}" not in results:
                continue
            r = results[f"{d}d_{key}"]
            pt = r["point"]
            speed = r["rate"] / base["rate"]
            binding = ", `--bind-to core`" if pt["kind"] == "binding" else ""
            w(f"| bench-{d}d | {pt['ranks']} x {pt['threads']}{binding} | {r['summary']['particles']:,} | "
              f"**{r['rate'] / 1e6:.2f}** ({rates(r['runs'])}) | {speed:.2f} | "
              f"{speed / (pt['ranks'] * pt['threads']):.2f} | {r['wall'] * 1e3:.0f} | {r['cpu'] * 1e3:.0f} | "
              f"{load_list(r['runs'])} |")
    w("")
    w("## Weak scaling (twice the particles on twice the ranks)")
    w("")
    w("The 2-rank input is the bench example with the body and the grid twice as long along the cut "
      "axis (y in 2-D, z in 3-D: the axis with the most bricks, along which the partition cuts), so each rank holds about the "
      "1-rank run's particles. Weak efficiency = 1-rank step time / 2-rank step time (wall; and CPU).")
    w("")
    w("| case | ranks x threads | particles | per rank (min-max) | M particle-steps/s (median; all runs) | wall ms per step | CPU ms per step | weak efficiency, wall | weak efficiency, CPU | load before each run |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    for d in (2, 3):
        one, two = results[f"{d}d_1x1"], results[f"{d}d_weak_2x1"]
        p = two["summary"]["parallel"]
        n1 = one["summary"]["particles"]
        w(f"| bench-{d}d | 1 x 1 | {n1:,} | {n1:,} | {one['rate'] / 1e6:.2f} | {one['wall'] * 1e3:.0f} | "
          f"{one['cpu'] * 1e3:.0f} | 1 | 1 | {load_list(one['runs'])} |")
        w(f"| bench-{d}d, twice as long | 2 x 1 | {two['summary']['particles']:,} | "
          f"{p['particles_per_rank']['min']:,}-{p['particles_per_rank']['max']:,} | "
          f"**{two['rate'] / 1e6:.2f}** ({rates(two['runs'])}) | {two['wall'] * 1e3:.0f} | {two['cpu'] * 1e3:.0f} | "
          f"**{one['wall'] / two['wall']:.2f}** | **{one['cpu'] / two['cpu']:.2f}** | {load_list(two['runs'])} |")
    w("")
    w("## The exchanges, counted by the code (summary.json `parallel`, the median run of each 2-rank point)")
    w("")
    w("Per rank, the larger of the two ranks' values. Seconds are wall time over the whole run; "
      "\"wait\" is the part inside the exchange itself (the messages and the wait for the other rank: "
      "the hand-off after each colour waits until the neighbour has scattered that colour, and the "
      "migration's all-to-all at the step's end waits for the slower rank), the rest is the rank's own "
      "packing, unpacking, scanning and compaction.")
    w("")
    keys = [
        ("particles per rank (min / max)", lambda p: f"{p['particles_per_rank']['min']:,} / {p['particles_per_rank']['max']:,}"),
        ("imbalance (max / mean)", lambda p: f"{p['particles_per_rank']['imbalance']:.3f}"),
        ("threads per rank; CPUs a rank may use", lambda p: f"{p['threads_per_rank']['max']}; {p['cpus_per_rank']['min']}"),
        ("hand-offs per step (colours with a neighbour)", lambda p: fmt(p["halo_exchanges_per_step"]["max"])),
        ("halo messages per step", lambda p: fmt(p["halo_messages_per_step"]["max"])),
        ("halo KB per step", lambda p: fmt(p["halo_bytes_per_step"]["max"] / 1e3)),
        ("halo ms per step (of which wait)", lambda p: f"{fmt(p['halo_seconds']['max'] / p['steps'] * 1e3)} ({fmt(p['halo_wait_seconds']['max'] / p['steps'] * 1e3)})"),
        ("migrated particles per step", lambda p: fmt(p["migrated_particles_per_step"]["max"])),
        ("migration messages per step", lambda p: fmt(p["migration_messages_per_step"]["max"])),
        ("migration KB per step", lambda p: fmt(p["migration_bytes_per_step"]["max"] / 1e3)),
        ("migration ms per step (of which wait)", lambda p: f"{fmt(p['migration_seconds']['max'] / p['steps'] * 1e3)} ({fmt(p['migration_wait_seconds']['max'] / p['steps'] * 1e3)})"),
        ("collectives per step (solver)", lambda p: fmt(p["collectives_per_step"]["max"])),
        ("collective ms per step", lambda p: fmt(p["collective_seconds"]["max"] / p["steps"] * 1e3)),
        ("step wall ms, slowest rank", lambda p: fmt(p["step_wall_seconds"]["max"] / p["steps"] * 1e3)),
        ("step CPU ms, busiest rank", lambda p: fmt(p["step_cpu_seconds"]["max"] / p["steps"] * 1e3)),
        ("CPU ms in the waits (exchanges, collectives)", lambda p: fmt(p["wait_cpu_seconds"]["max"] / p["steps"] * 1e3)),
        ("work CPU ms (step CPU outside the waits), busiest rank", lambda p: fmt(p["work_cpu_seconds"]["max"] / p["steps"] * 1e3)),
    ]
    cols = [k for k in results if results[k]["point"]["ranks"] > 1]
    w("| counter | " + " | ".join(results[k]["point"]["label"] for k in cols) + " |")
    w("|---|" + "---|" * len(cols))
    for label, get in keys:
        w(f"| {label} | " + " | ".join(get(results[k]["summary"]["parallel"]) for k in cols) + " |")
    w("")

    # ---- the model
    cal = {d: calibrate(results, d) for d in (2, 3)}
    costs = {d: exchange_costs(results[f"{d}d_2x1"]) for d in (2, 3)}
    w("## The model")
    w("")
    w("Time per step of a rank, one thread per rank (the slowest rank sets the step):")
    w("")
    w("    T = n c_p + N_n c_n + (M_h a + B_h / b + B_h c_h) + (n c_m + M_m a + B_m / b) + K (2 log2(P) a + 8 P / b)")
    w("")
    w("- n: the rank's particles (the largest rank's, so the imbalance is in it); c_p: CPU seconds per "
      "particle-step, from the 1-rank run;")
    w(f"- N_n: grid nodes the rank loops over; c_n: CPU seconds per node-step, from the 1-rank run on a "
      f"grid {WIDE} times as long along x with the same body (the difference of the two step times "
      "over the difference of their node counts). Each rank stores and loops over its **window** of "
      "the grid (docs/scale-out.md §2, since session 27): its owned and ghost nodes, counted by the "
      "run (`stored_nodes_per_rank`); before it every rank looped over the whole grid. Both are "
      "modelled;")
    w("- M_h, B_h: the hand-off's messages and bytes per step of the rank (counted); a, b: latency "
      "and bandwidth; c_h: the packing and unpacking per byte;")
    w("- c_m: the migration's own work per particle-step (the owner of every particle's cell and the "
      "stable compaction of every array, every step, whether or not a particle leaves); M_m, B_m: "
      "migration messages and bytes (counted);")
    w("- K: collectives per step (the dt, the stencils' reach and the failure record, counted, plus the "
      "run loop's interrupt flag), each a tree of 2 log2 P latencies; the rank-order sums gather P "
      "values (8 P bytes).")
    w("")
    w("**Calibration.** c_p and c_n from the median CPU time per step of the 1-rank runs; c_m and c_h "
      "from the 2 x 1 strong run of each dimension (the CPU time of the hand-off and the migration "
      "outside their exchanges, `halo_own_cpu_seconds`, `migration_own_cpu_seconds`); a = 1 us and b = 1.9 GB/s for this "
      "machine from docs/scale-out.md §13's plain exchange (a p10 fit, within 35 %), not from the "
      "counters' wait seconds, which hold the wait for the other rank more than the wire.")
    w("")
    w("| | c_p (us per particle-step) | c_n (ns per node-step) | nodes; wide grid's | CPU ms per step: 1 x 1, wide | node share of the 1-rank step | c_m (ns per particle-step) | c_h (ns per byte) |")
    w("|---|---|---|---|---|---|---|---|")
    for d in (2, 3):
        c, e = cal[d], costs[d]
        w(f"| bench-{d}d | {c['c_p'] * 1e6:.4f} | {c['c_n'] * 1e9:.1f} | {c['nodes']:,}; {c['wide_nodes']:,} | "
          f"{c['t1'] * 1e3:.0f}, {c['tw'] * 1e3:.0f} | {c['c_n'] * c['nodes'] / c['t1'] * 100:.1f} % | "
          f"{e['c_m'] * 1e9:.1f} | {e['c_h'] * 1e9:.2f} |")
    w("")
    w("**Check against the measured 2-rank points.** The ranks' own work (particles, grid, and the "
      "hand-off's and the migration's own work) against the busiest rank's CPU time in the steps "
      "outside the exchanges' and collectives' waits (`work_cpu_seconds`); the weak points are an "
      "independent check of c_m and c_h, all points of c_p and c_n. Then the model's wire time "
      "(messages, bytes, collectives at this machine's a and b) beside the measured wait:")
    w("")
    w("| point | particles (largest rank) | T particles | T grid (the window) | T own exchange work | model work | measured work CPU | model / measured | model wire | measured wait, CPU / wall |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    ratios = []
    for k in cols:
        r = results[k]
        if r["point"]["threads"] != 1:
            continue
        d = r["point"]["dim"]
        p = r["summary"]["parallel"]
        t, terms = predict_measured(r, cal[d], costs[d])
        work = terms["particles"] + terms["grid"] + terms["own"]
        wire = terms["halo"] + terms["migration"] + terms["collectives"]
        measured = statistics.median(x["summary"]["parallel"]["work_cpu_seconds"]["max"] / x["summary"]["steps"]
                                     for x in r["runs"])
        wait_wall = (p["halo_wait_seconds"]["max"] + p["migration_wait_seconds"]["max"]
                     + p["collective_seconds"]["max"]) / p["steps"]
        ratio = work / measured
        ratios.append((r["point"]["label"], ratio))
        w(f"| {r['point']['label']} | {p['particles_per_rank']['max']:,} | "
          + " | ".join(f"{terms[x] * 1e3:.2f}" for x in ("particles", "grid", "own"))
          + f" | {work * 1e3:.1f} | {measured * 1e3:.1f} | **{ratio:.2f}** | {wire * 1e3:.2f} | "
          f"{p['wait_cpu_seconds']['max'] / p['steps'] * 1e3:.1f} / {wait_wall * 1e3:.1f} |")
    worst_label, worst = max(ratios, key=lambda x: abs(x[1] - 1))
    w("")
    w(f"Stated error of the model: **+-{STATED_ERROR * 100:.0f} %** in CPU time (the runs of one point "
      f"spread by up to 10 % in CPU time on this machine, far more in wall time). Largest deviation: "
      f"{(worst - 1) * 100:+.0f} % ({worst_label}): " +
      ("within it." if abs(worst - 1) <= STATED_ERROR else
       "**outside it**: the model misses part of the ranks' work on this machine (the gap is carried "
       "into the remarks under the predictions)."))
    wall_waits = []
    for k in cols:
        p = results[k]["summary"]["parallel"]
        waits = (p["halo_wait_seconds"]["max"] + p["migration_wait_seconds"]["max"] + p["collective_seconds"]["max"])
        wall_waits.append(f"{results[k]['point']['label']} {waits / p['step_wall_seconds']['max'] * 100:.0f} %")
    w("")
    w("**The waits.** The 2-rank steps wait for each other: the share of the slowest rank's wall time "
      "spent inside the exchanges and collectives was " + ", ".join(wall_waits) + ". On an idle "
      "machine that is the ranks' imbalance plus the wire (the model's wire column); on a loaded one "
      "mostly the other processes taking one rank's core while the other waits (every colour's "
      "hand-off is a synchronisation point: 4 per step in 2-D, 8 in 3-D). OpenMPI polls while it "
      "waits, so the waits cost CPU time too (the wait CPU column); the model's work is compared "
      "without them.")
    w("")
    # ---- predictions
    r3 = results["3d_weak_2x1"]
    p3 = r3["summary"]["parallel"]
    spec3 = r3["point"]["spec"]
    cx, cy, _ = cells(spec3)
    box = spec3["bodies"][0]["shape"]
    h = spec3["grid"]["cell_size"]
    body_face_cells = ((box["max"][0] - box["min"][0]) / h) * ((box["max"][1] - box["min"][1]) / h)
    moved = p3["migrated_particles_per_step"]["sum"]
    counters = {
        "halo_bytes_per_plane_node": p3["halo_bytes_per_step"]["max"] / ((cx + 1) * (cy + 1)),
        "halo_messages_per_neighbour": p3["halo_messages_per_step"]["max"],
        "migrated_per_face_cell": max(p3["migrated_particles_per_step"]["max"] / body_face_cells, 0.8),
        "bytes_per_particle": p3["migration_bytes_per_step"]["sum"] / moved if moved > 0 else BYTES_PER_PARTICLE_3D,
        "collectives_per_step": p3["collectives_per_step"]["max"] + 1,
        "doubles_per_node": 20,
    }
    w("## Predictions: bench-3d scaled up to 64 and 1024 ranks")
    w("")
    w("**What \"scaled up\" means.** Weak scaling at bench-3d's particles per rank: every rank holds "
      "512 000 particles (bench-3d's 40 x 40 x 40 cells of 2 x 2 x 2 particles, the measured weak "
      "point), and, as a second case, 10^6. Two shapes of the whole body:")
    w("")
    w("- **rod, slabs**: bench-3d's 40 x 40-cell cross-section, the body P times as long along z; each "
      "rank a slab 40 cells thick (5 brick layers of 8 cells; 78 cells at 10^6) with two neighbours. "
      "This continues the measured weak-scaling case; slabs do not run out.")
    w("- **cube, RCB boxes**: a cube of 64 000 P cells (P x bench-3d's block). Slabs along one axis run "
      "out at cells_z / 8 ranks (one brick layer each): the cube is (64 000 P)^(1/3) cells a side, "
      "25 layers at P = 64 and 63 at P = 1024, fewer than the ranks. A cube on 64 or 1024 ranks "
      "therefore needs the recursive bisection boxes of docs/scale-out.md §10 (built in session 29; "
      "tested bitwise on 4 ranks as 2 x 2 boxes): each rank a box of 40^3 cells (50^3 at 10^6) with 6 "
      "face, 12 edge and 8 corner neighbours. (The boxes are whole bricks of 32 x 8 x 8 cells, so at "
      "P = 1024 a rank's box is rather 64 x 32 x 32 cells, with 7 % more surface than 40^3; the model "
      "keeps the cube. Slabs "
      "could serve a cube only with cells_z >= 8 P, i.e. >= 4096 P^2 particles per rank: 1.7 x 10^7 "
      "at P = 64, 4.3 x 10^9 at 1024.)")
    w("")
    w(f"**Assumptions.** Interconnect latency a = {CLUSTER_LATENCY * 1e6:.1f} us per message (typical "
      f"1-2 us), bandwidth b = {CLUSTER_BANDWIDTH / 1e9:.1f} GB/s per rank (10-25 GB/s); one rank per core, "
      "c_p, c_n, c_m, c_h of this machine's core; no overlap of communication and computation (the "
      "hand-off is synchronous per colour, as built). From the measured 3-D weak run: "
      f"{fmt(counters['halo_bytes_per_plane_node'])} halo bytes per node of a cut plane per step (the "
      "hand-off sends a plane's nodes across the whole grid, 4 node layers of 7 values), "
      f"{fmt(counters['halo_messages_per_neighbour'])} messages per neighbour and step. Every box "
      "neighbour counted as a face neighbour for the messages (an upper bound: edges and corners "
      "share fewer colours). Migration: bench-3d moves no particle across a cut within its 20 steps "
      "(its speeds move a particle about 0.03 cells), so the model assumes a flow that does: "
      f"{fmt(counters['migrated_per_face_cell'])} particles per face cell per step (8 per cell, "
      f"moving 0.1 cell per step) of {fmt(counters['bytes_per_particle'])} B each, across every face. "
      "Imbalance 1.0 (the partition balances the particle count; the measured 2-rank imbalance is in "
      f"the counters' table). Grid memory: {counters['doubles_per_node']} doubles per node.")
    w("")
    w("| shape, partition | grid loops | particles per rank | P | T particles | T grid | T own exchange work | T halo wire | T migration wire | T collectives | ms per step | efficiency | grid GiB per rank |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    predictions = {}
    for per_rank in (512_000, 1_000_000):
        for geometry in ("rod", "cube"):
            for windowed in (False, True):
                for P in (2, 64, 1024):
                    m = scaled_up(P, per_rank, cal[3], costs[3], counters, geometry, windowed)
                    predictions[(per_rank, geometry, windowed, P)] = m
                    w(f"| {geometry}, {'slabs' if geometry == 'rod' else 'RCB boxes'} | "
                      f"{'window' if windowed else 'whole grid'} | {per_rank:,} | {P} | "
                      + " | ".join(f"{m[x] * 1e3:.2f}" for x in ("particles", "grid", "own", "halo", "migration", "collectives"))
                      + f" | {m['t'] * 1e3:.0f} | **{m['efficiency'] * 100:.0f} %** | {m['grid_gib']:.2f} |")
    w("")
    cw = predictions[(512_000, "cube", True, 1024)]
    rw = predictions[(512_000, "rod", True, 1024)]
    cwhole64 = predictions[(512_000, "cube", False, 64)]
    cwhole = predictions[(512_000, "cube", False, 1024)]
    comm = (cw["halo"] + cw["collectives"] + cw["migration"]) / cw["t"]
    w("Efficiency = the step time of one rank alone with the same particles on its own grid / the "
      "step time of a rank on P ranks (weak scaling). What the table says:")
    w("")
    overhead = {"the grid loops over the window": cw["grid"], "the halo's wire": cw["halo"],
                "the hand-off's and the migration's own work (c_h, c_m)": cw["own"],
                "the migration's wire": cw["migration"], "the collectives": cw["collectives"]}
    largest = max(overhead, key=overhead.get)
    w(f"- **With the window** the particle work dominates at every P: at 1024 ranks the wire of the cube's "
      f"halo and migration and its collectives are {comm * 100:.1f} % of a {cw['t'] * 1e3:.0f} ms step; the "
      f"efficiency ({cw['efficiency'] * 100:.0f} % for RCB boxes, {rw['efficiency'] * 100:.0f} % for the "
      f"slabs) is lost mostly to {largest} ({overhead[largest] / cw['t'] * 100:.1f} % of the step), "
      "not to the network, and it hardly falls from 64 to 1024 ranks (only the collectives grow, as "
      "log2 P).")
    w(f"- **Without the window** (the code before session 27) every rank looped over and stored the "
      f"whole grid: the cube at 64 ranks would run at {cwhole64['efficiency'] * 100:.0f} %, at 1024 at "
      f"{cwhole['efficiency'] * 100:.0f} % with {cwhole['grid_gib']:.0f} GiB of grid per rank. The window "
      "of docs/scale-out.md §2, built since, is the precondition for any scale-out beyond a few ranks.")
    w(f"- The migration's own work costs c_m = {costs[3]['c_m'] * 1e9:.0f} ns per particle-step in 3-D "
      f"({costs[2]['c_m'] * 1e9:.0f} ns in 2-D) against c_p = {cal[3]['c_p'] * 1e9:.0f} ns: every step "
      "it finds every particle's owner and compacts every array even when no particle leaves. Testing "
      "only the particles whose cell changed (the stencils know each particle's cell) and compacting "
      "only when one left would remove most of it.")
    gap = min(r for _, r in ratios)
    if gap < 1 - 0.05:
        w(f"- The 2-rank check leaves up to {(1 - gap) * 100:.0f} % of the measured work unexplained; "
          "were it a real cost of every rank's step, these efficiencies would be lower by as much.")
    w("- Latency matters only for small ranks: a rank with 26 neighbours sends at most "
      f"{fmt(26 * counters['halo_messages_per_neighbour'])} hand-off messages per step, "
      f"{26 * counters['halo_messages_per_neighbour'] * CLUSTER_LATENCY * 1e3:.2f} ms at "
      f"{CLUSTER_LATENCY * 1e6:.1f} us: nothing next to a step of 512 000 particles, but comparable "
      "to the work at a few thousand particles per rank.")
    w("- **The waits are not predicted**: the model's step is the busiest rank's work plus the wire. "
      "What a rank loses waiting for a slower one beyond the particle imbalance (OS noise, cache "
      "effects, a shared node) adds at every colour's hand-off (8 synchronisations per 3-D step) and "
      "grows with P; on this loaded machine it was the largest loss (the waits above). Measure it on "
      "the cluster: the counters' `*_wait_seconds` say how much of it there is.")
    w("- Not modelled: overlap (none is built), the OpenMP threads inside a rank (the model is per "
      "core; the measured 2-thread points are in the strong-scaling table), network contention, "
      "re-partitioning (§10), output and checkpoints; the collectives are modelled as latency-bound "
      "trees although the rank-order sums are all-gathers (8 P bytes each: 8 KB at 1024 ranks).")
    w("")

    # ---- threads x ranks
    two_two = results.get("2d_2x2")
    bound = results.get("2d_2x2_bound")
    w("## Threads x ranks")
    w("")
    w("`--threads T` (or `OMP_NUM_THREADS`, when `--threads` is not given) sets each rank's OpenMP "
      "threads; summary.json reports `parallel.threads_per_rank` and `parallel.cpus_per_rank` (the "
      "CPUs the rank's affinity mask allows), and the run warns when a rank has more threads than CPUs. "
      "`tests/mpi/threads_ranks.sh` checks that 2 ranks x 2 threads equal the serial one-thread run "
      "bit for bit and that both settings are honoured per rank.")
    w("")
    if two_two and bound:
        w(f"2 ranks x 2 threads on 2 cores (4 threads; `main` sets the passive wait policy, so waiting "
          f"threads sleep): bench-2d {two_two['rate'] / 1e6:.2f} M particle-steps/s with "
          f"`--bind-to none`, against {results['2d_2x1']['rate'] / 1e6:.2f} for 2 x 1 and "
          f"{results['2d_1x2']['rate'] / 1e6:.2f} for 1 x 2: "
          + ("no collapse. " if two_two["rate"] >= 0.8 * min(results["2d_2x1"]["rate"], results["2d_1x2"]["rate"])
             else "**slower**. ")
          + f"With mpirun's default binding (`--bind-to core`: OpenMPI binds each of 2 ranks to one core) "
          f"a rank's 2 threads share one core (`cpus_per_rank` "
          f"{bound['summary']['parallel']['cpus_per_rank']['min']}; the run warns): "
          f"{bound['rate'] / 1e6:.2f} M/s, {bound['rate'] / two_two['rate']:.2f} x the unbound rate"
          + (" (on this loaded machine every process shares the cores anyway, so binding costs little "
             "here; on an idle one the bound rank's second thread has no core of its own). "
             if loaded else ". ")
          + "Start ranks that have several threads with `mpirun --bind-to none` or `--map-by slot:PE=T` "
          "(T cores per rank).")
        w("")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("matpoint", nargs="?", default=os.path.join(ROOT, "build-mpi", "matpoint"))
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--mpirun-args", default="--bind-to none",
                    help="more mpirun options (default --bind-to none: a rank's threads may use every core)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "scaling.md"))
    ap.add_argument("--work", default="/tmp/matpoint-scaling")
    ap.add_argument("--only", default="", help="comma-separated point names: a quick look, no report")
    ap.add_argument("--report-only", action="store_true", help="rewrite the report from WORK/runs.json")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    pts = points(args, args.work)
    saved = os.path.join(args.work, "runs.json")
    if args.report_only:
        data = json.load(open(saved))
        runs, elapsed, finished = data["runs"], data["elapsed"], data.get("finished")
    else:
        if args.only:
            pts = [p for p in pts if p["name"] in args.only.split(",")]
        runs = {p["name"]: [] for p in pts}
        t0 = time.monotonic()
        for repeat in range(args.repeats):
            for p in pts:
                r = run_point(args, p, args.work, repeat)
                runs[p["name"]].append(r)
                s = r["summary"]
                print(f"[{repeat + 1}/{args.repeats}] {p['label']:>14}: {s['particle_steps_per_second'] / 1e6:6.2f} M/s, "
                      f"{wall_per_step(s) * 1e3:7.1f} wall ms, {cpu_per_step(s) * 1e3:7.1f} CPU ms per step, "
                      f"load {r['load_before']:.1f}, process {r['process_wall']:.1f} s", flush=True)
        elapsed = time.monotonic() - t0
        finished = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
        with open(saved, "w") as f:
            json.dump({"elapsed": elapsed, "finished": finished, "runs": runs}, f)
        if args.only:
            return
    text = report(args, pts, runs, elapsed, finished)
    with open(args.out, "w") as f:
        f.write(text)
    print(f"wrote {args.out} ({elapsed / 60:.1f} minutes of runs)")


if __name__ == "__main__":
    main()
