#!/usr/bin/env python3
"""Iaconeta 2017 §5.1 (Fig. 7) side by side: the static cantilever (input.json) solved by the
implicit UL MPM (solver.basis "mesh") and the Galerkin meshfree method with MLS and LME functions
(solver.basis "mls", "lme"; §4.2), on the same input at each cell size h. Prints Point A's deflection
(output.node_probes "A": the free end's mid-height), its error against the paper's finest-mesh value
0.67433 m, the observed order between successive h, and the run's wall time.

    examples/cantilever-static/compare.py BUILD/matpoint [--h 0.5,0.25,0.125] [--radius-factor F]

--radius-factor: R / h of the meshfree clouds (default: the input's default 2 sqrt(2); the paper's
"R = 2h2" read as sqrt(2) is 1.4142), R_eff = R / 2. README.md has the last output.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PAPER = 0.67433  # m, Iaconeta 2017 §5.1, finest mesh


def load(name):
    text = open(os.path.join(HERE, name)).read()
    return json.loads("\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//")))


def case(basis, h, radius_factor):
    spec = load("input.json")
    spec["mesh"]["cells"] = [round(8 / h), round(1 / h)]
    spec["solver"]["basis"] = basis
    if basis != "mesh" and radius_factor:
        spec["solver"]["meshfree"] = {"radius_factor": radius_factor}
    spec["checks"] = [{"name": "Point A", "measure": "node_probe_final_uy", "expected": 0, "tolerance": 0,
                       "kind": "regression", "source": "reported by compare.py"}]
    spec["output"]["particles"] = False
    return spec


def run(binary, spec):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "input.json")
        json.dump(spec, open(path, "w"))
        out = os.path.join(tmp, "out")
        done = subprocess.run([binary, "run", path, "--out", out, "--threads", "1"], check=False,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            sys.exit(f"{binary} failed ({done.returncode}): {done.stderr}")
        summary = json.load(open(os.path.join(out, "summary.json")))
    return summary["checks"][0]["measured"], summary["wall_time_seconds"]


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    binary = argv[1]
    hs = [float(h) for h in argv[argv.index("--h") + 1].split(",")] if "--h" in argv else [0.5, 0.25, 0.125]
    radius = float(argv[argv.index("--radius-factor") + 1]) if "--radius-factor" in argv else None
    print(f"R / h = {radius or 2 * math.sqrt(2):.4f} (meshfree), error against {PAPER} m")
    print(f"{'method':8} {'h (m)':>7} {'u_y(A) m':>10} {'error m':>9} {'order':>6} {'wall s':>7}")
    for basis, name in (("mesh", "MPM"), ("mls", "GMM-MLS"), ("lme", "GMM-LME")):
        previous = None
        for h in hs:
            uy, wall = run(binary, case(basis, h, radius))
            error = abs(PAPER + uy)
            order = f"{math.log2(previous / error):6.2f}" if previous else f"{'':6}"
            print(f"{name:8} {h:7.4f} {uy:10.6f} {error:9.5f} {order} {wall:7.2f}", flush=True)
            previous = error


if __name__ == "__main__":
    main(sys.argv)
