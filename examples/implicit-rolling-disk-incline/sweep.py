#!/usr/bin/env python3
"""Iaconeta 2017 §5.2 Table 1's time-step study for the MPM row: the disk on the 60 degree
incline at dt1 = 1e-3, dt2 = 5e-4, dt3 = 2.5e-4 s to t_end = 1 s on the paper's T3 mesh
(h = 0.01 m), with the no-slip one-sided floor (no-slip.json), with --fixed also the plain
held floor (no-slip.json without one_sided: it glues the disk), and the frictionless control
(input.json's floor, on no-slip.json's mesh, run length and resolution; its mesh is longer so that the
disk stays on it for 1 s). Prints per run the fitted acceleration over the rolling one
(rolling_acceleration_ratio: 1 rolling, 1.5 sliding), the relative error of the displacement at
t_end against rolling (rolling_final_displacement_error), eq. (67) with outputs every 0.01 s
(rolling_displacement_error_norm, m), the wall time and Newton's iterations, beside Table 1's MPM row.

    examples/implicit-rolling-disk-incline/sweep.py BUILD/matpoint [--quick] [--fixed] [--diagonal PATTERN]
                                                   [--bspline]

--quick: h = 0.02 m and t_end = 0.3 s (seconds instead of minutes). --bspline: the C1 B-spline
background of bspline.json (cells of the same h, 2 x 2 particles per cell, soft stiffness) instead of
the T3 mesh. README.md has the last output.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TABLE1_MPM = {1e-3: (2.34, 232.72), 5e-4: (1.27, 472.92), 2.5e-4: (0.91, 894.91)}  # error (m), t_comp (s)
MEASURES = ["rolling_acceleration_ratio", "rolling_final_displacement_error", "rolling_displacement_error_norm"]


def load(name):
    text = open(os.path.join(HERE, name)).read()
    return json.loads("\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//")))


def case(floor, dt, quick, diagonal, bspline=False):
    spec = load("bspline.json" if bspline else "no-slip.json")
    if quick:
        spec["mesh"]["cells"] = [spec["mesh"]["cells"][0] // 2, spec["mesh"]["cells"][1] // 2]
        spec["solver"]["end_time"] = 0.3
    if diagonal:
        spec["mesh"]["diagonal"] = diagonal
    if floor == "fixed":
        spec["boundary_conditions"][0]["one_sided"] = False
    if floor == "slip":
        spec["boundary_conditions"] = load("input.json")["boundary_conditions"]
        h = spec["mesh"]["max"][0] / spec["mesh"]["cells"][0]
        spec["mesh"]["max"][0] = 5.0  # 0.5 g sin(60) t^2 = 4.25 m in 1 s
        spec["mesh"]["cells"][0] = round(5.0 / h)
    spec["solver"]["dt"] = dt
    spec["checks"] = [{"name": m, "measure": m, "expected": 0, "tolerance": 0, "kind": "regression",
                       "source": "reported by sweep.py"} for m in MEASURES]
    return spec


def run(binary, spec):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "input.json")
        json.dump(spec, open(path, "w"))
        out = os.path.join(tmp, "out")
        subprocess.run([binary, "run", path, "--out", out, "--threads", "1"], check=False,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        summary = json.load(open(os.path.join(out, "summary.json")))
    measured = {c["measure"]: c["measured"] for c in summary["checks"]}
    return measured, summary


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    binary, quick, bspline = argv[1], "--quick" in argv, "--bspline" in argv
    diagonal = argv[argv.index("--diagonal") + 1] if "--diagonal" in argv else None
    print(f"{'floor':8} {'dt (s)':>8} {'a / (2/3 g sin)':>15} {'u(t_end) err':>12} {'eq. (67) m':>10} "
          f"{'wall s':>7} {'Newton':>6}   Table 1 MPM: {'error m':>7} {'t_comp s':>8}")
    floors = ("no-slip", "fixed", "slip") if "--fixed" in argv else ("no-slip", "slip")
    for floor in floors:
        for dt in (1e-3, 5e-4, 2.5e-4):
            measured, summary = run(binary, case(floor, dt, quick, diagonal, bspline))
            implicit = summary.get("implicit", {})
            paper = TABLE1_MPM[dt] if floor == "no-slip" else ("", "")
            print(f"{floor:8} {dt:8.2e} {measured[MEASURES[0]]:15.4f} {measured[MEASURES[1]]:12.4f} "
                  f"{measured[MEASURES[2]]:10.4f} {summary['wall_time_seconds']:7.1f} "
                  f"{implicit.get('newton_iterations', 0):6}   {'':13}{paper[0]:>7} {paper[1]:>8}", flush=True)


if __name__ == "__main__":
    main(sys.argv)
