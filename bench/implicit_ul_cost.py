#!/usr/bin/env python3
"""Issue 20's performance table: the implicit updated-Lagrangian MPM (Iaconeta et al. 2017) on
examples/cantilever-static at h = 0.0625 m and on examples/soil-column-collapse (implicit.json),
beside the explicit solver on the same column (input.json) for the same physical time (2 s).

    python3 bench/implicit_ul_cost.py [build/matpoint] [--repeats 3] [--threads 1]

Every run `--repeats` times, interleaved (cantilever, explicit column, implicit column, then again),
with the load average (`uptime`, 1 minute) read before and after each run, since the machine may be
shared. The inputs are the examples' own, unchanged, but for the cantilever's cells ([128, 16]:
h = 0.0625 m) and no plots or particle files (output.particles false; output.plots false), so
that the wall times are the solvers'. Reads summary.json (docs/output.md: `step_wall_seconds`,
`step_cpu_seconds`, `steps`, `implicit.assembly_seconds`, `implicit.factorization_seconds`, `implicit.solve_seconds`,
`implicit.newton_iterations`) and prints one row per run and a table of min and spread (max - min)
per case. Python 3 standard library only.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_input(path):
    """An example's input (JSON with // comment lines)."""
    text = "\n".join(line for line in open(path) if not line.lstrip().startswith("//"))
    return json.loads(text)


def load_average():
    return os.getloadavg()[0]


def cases(work):
    """(name, input path) of the three runs, written into `work`."""
    out = []
    cantilever = read_input(os.path.join(ROOT, "examples/cantilever-static/input.json"))
    cantilever["mesh"]["cells"] = [128, 16]  # h = 0.0625 m
    cantilever["checks"] = []  # the h = 0.5 m check does not apply at h = 0.0625
    cantilever["output"]["particles"] = False
    cantilever["output"]["plots"] = False
    column_dir = os.path.join(ROOT, "examples/soil-column-collapse")
    for name, spec in (("cantilever h=0.0625 (implicit_ul static)", cantilever),
                       ("column explicit (input.json)", read_input(os.path.join(column_dir, "input.json"))),
                       ("column implicit_ul (implicit.json)", read_input(os.path.join(column_dir, "implicit.json")))):
        spec["output"]["particles"] = False
        spec["output"]["plots"] = False
        path = os.path.join(work, f"case{len(out)}.json")
        json.dump(spec, open(path, "w"))
        out.append((name, path))
    return out


def run(binary, path, out, threads):
    load_before = load_average()
    start = time.monotonic()
    subprocess.run([binary, "run", path, "--out", out, "--overwrite", "--quiet", "--threads", str(threads)],
                   check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    elapsed = time.monotonic() - start
    s = json.load(open(os.path.join(out, "summary.json")))
    imp = s.get("implicit", {})
    return {
        "load_before": load_before,
        "load_after": load_average(),
        "process_seconds": elapsed,
        "status": s.get("status"),
        "time_reached": s["time_reached"],
        "steps": s["steps"],
        "particles": s["particles"],
        "step_wall": s["step_wall_seconds"],
        "step_cpu": s["step_cpu_seconds"],
        "assembly": imp.get("assembly_seconds"),
        "factorization": imp.get("factorization_seconds"),
        "solve": imp.get("solve_seconds"),
        "newton": imp.get("newton_iterations"),
        "nodes": imp.get("mesh_nodes", s.get("nodes")),
    }


def spread(values):
    return min(values), max(values) - min(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("binary", nargs="?", default=os.path.join(ROOT, "build/matpoint"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    results = {}
    with tempfile.TemporaryDirectory() as work:
        runs = cases(work)
        for repeat in range(args.repeats):
            for name, path in runs:
                r = run(args.binary, path, os.path.join(work, "out"), args.threads)
                results.setdefault(name, []).append(r)
                per_step = (f" assembly {r['assembly'] / r['steps'] * 1e3:.2f} ms/step, LU "
                            f"{r['factorization'] / r['steps'] * 1e3:.2f} ms/step, solves "
                            f"{r['solve'] / r['steps'] * 1e3:.2f} ms/step, Newton {r['newton']}"
                            if r["assembly"] is not None else "")
                print(f"[{repeat + 1}] {name}: status {r['status']}, t = {r['time_reached']:.3f} s, "
                      f"{r['steps']} steps, step wall {r['step_wall']:.3f} s, CPU {r['step_cpu']:.3f} s,{per_step} "
                      f"(load {r['load_before']:.2f} -> {r['load_after']:.2f})", flush=True)
    print(f"\n{args.threads} thread(s), {args.repeats} runs each, interleaved; min and spread (max - min)")
    print("| case | particles | steps | step wall [s] | step CPU [s] | per step [ms] | assembly / step [ms] | "
          "LU (analysis + factorisation) / step [ms] | triangular solves / step [ms] | Newton / step | "
          "load average (1 min) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, rs in results.items():
        steps = rs[0]["steps"]
        wall = spread([r["step_wall"] for r in rs])
        cpu = spread([r["step_cpu"] for r in rs])
        per = spread([r["step_wall"] / r["steps"] * 1e3 for r in rs])
        loads = [r["load_before"] for r in rs] + [r["load_after"] for r in rs]
        row = [name, str(rs[0]["particles"]), str(steps), f"{wall[0]:.3g} (+{wall[1]:.2g})",
               f"{cpu[0]:.3g} (+{cpu[1]:.2g})",
               f"{per[0]:.3g} (+{per[1]:.2g})"]
        if rs[0]["assembly"] is not None:
            for key in ("assembly", "factorization", "solve"):
                m, d = spread([r[key] / r["steps"] * 1e3 for r in rs])
                row.append(f"{m:.3g} (+{d:.2g})")
            row.append(f"{rs[0]['newton'] / steps:.2f}")
        else:
            row += ["", "", "", ""]
        row.append(f"{min(loads):.1f}-{max(loads):.1f}")
        print("| " + " | ".join(row) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
