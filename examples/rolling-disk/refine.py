#!/usr/bin/env python3
"""Iaconeta 2017 §5.2 rolling disk: centre-of-mass acceleration along the incline versus the cell
size, for the no-slip ("fixed") and the frictionless ("slip") one-sided incline face.

Usage: python3 examples/rolling-disk/refine.py [MATPOINT] [--cells 0.04,0.02,0.01] [--threads 2]
       [--end-time 0.3] [--shape cpgimp]
Prints a Markdown table: a / (2/3 g sin 60) for the no-slip face and a / (g sin 60) for the slip
face, a from the displacement fit x(t) - x(0) = a t^2 / 2 (the example's measure) and, for the
no-slip face, also from the slope of the velocity, and the largest rise of the disk's centre.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402

G_SIN = 9.81 * math.sin(math.radians(60))
MEASURES = ("fitted_com_displacement_acceleration_x", "fitted_com_acceleration_x")


def run_face(matpoint, base, face, h, end_time, shape, threads):
    """(displacement-fit a, velocity-slope a, largest rise of the centre in m, summary)."""
    spec = variant(base, solver={"end_time": end_time, "basis": shape},
                   output={"every_time": 0.005, "particles": False, "plots": False})
    spec["grid"]["cell_size"] = h
    spec["boundary_conditions"][0]["type"] = face
    spec["checks"] = [{"name": m, "measure": m, "expected": 0, "tolerance": 1e9, "source": "refine.py"}
                      for m in MEASURES]
    result = run_spec(matpoint, spec, threads)
    if not result.ok:
        return float("nan"), float("nan"), float("nan"), result.summary
    a_disp, a_slope = (c["measured"] for c in result.summary["checks"])
    y = result.column("body0_com_y")
    return a_disp, a_slope, max(y) - y[0], result.summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--cells", default="0.04,0.02,0.01")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--end-time", type=float, default=0.3)
    parser.add_argument("--shape", default="cpgimp")
    args = parser.parse_args()
    base = load_input(HERE)
    roll_exact = 2 * G_SIN / 3
    print(f"shape {args.shape}, end time {args.end_time} s; exact: rolling 2/3 g sin 60 = {roll_exact:.4f}, "
          f"sliding g sin 60 = {G_SIN:.4f} m/s^2\n")
    print("| h (m) | R / h | particles | no-slip a (m/s²) | / (2/3 g sin θ) | velocity slope / (2/3 g sin θ) "
          "| rise of the centre (mm) | slip a / (g sin θ) | wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for h in [float(h) for h in args.cells.split(",")]:
        roll, slope, rise, s1 = run_face(args.matpoint, base, "fixed", h, args.end_time, args.shape, args.threads)
        slide, _, _, s2 = run_face(args.matpoint, base, "slip", h, args.end_time, args.shape, args.threads)
        wall = s1.get("wall_time_seconds", 0) + s2.get("wall_time_seconds", 0)
        print(f"| {h} | {0.2 / h:.0f} | {s1.get('particles', '?')} | {roll:.4f} | {roll / roll_exact:.4f} | "
              f"{slope / roll_exact:.4f} | {1000 * rise:.1f} | {slide / G_SIN:.4f} | {wall:.0f} |", flush=True)


if __name__ == "__main__":
    main()
