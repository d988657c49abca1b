#!/usr/bin/env python3
"""Iaconeta 2017 §5.2 rolling disk: fitted centre-of-mass acceleration along the incline versus the
cell size, for the no-slip ("fixed") and the frictionless ("slip") incline face.

Usage: python3 examples/rolling-disk/refine.py [MATPOINT] [--cells 0.04,0.02,0.01] [--threads 2]
       [--end-time 0.3] [--shape cpgimp]
Prints a Markdown table: a / (2/3 g sin 60) for the no-slip face, a / (g sin 60) for the slip face.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402

G_SIN = 9.81 * math.sin(math.radians(60))


def fitted_acceleration(matpoint, base, face, h, end_time, shape, threads):
    spec = variant(base, solver={"end_time": end_time, "shape": shape},
                   output={"every_time": 0.01, "particles": False, "plots": False})
    spec["grid"]["cell_size"] = h
    spec["boundary_conditions"][0]["type"] = face
    spec["checks"] = [{"name": "a", "measure": "fitted_com_acceleration_x", "expected": 0, "tolerance": 1e9,
                       "source": "refine.py"}]
    result = run_spec(matpoint, spec, threads)
    if not result.ok:
        return float("nan"), result.summary
    return result.summary["checks"][0]["measured"], result.summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--cells", default="0.04,0.02,0.01")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--end-time", type=float, default=0.3)
    parser.add_argument("--shape", default="cpgimp")
    args = parser.parse_args()
    base = load_input(HERE)
    print(f"shape {args.shape}, end time {args.end_time} s; exact: rolling 2/3 g sin 60 = {2 * G_SIN / 3:.4f}, "
          f"sliding g sin 60 = {G_SIN:.4f} m/s^2\n")
    print("| h (m) | R / h | particles | no-slip a (m/s²) | / (2/3 g sin θ) | slip a (m/s²) | / (g sin θ) | wall s |")
    print("|---|---|---|---|---|---|---|---|")
    for h in [float(h) for h in args.cells.split(",")]:
        roll, s1 = fitted_acceleration(args.matpoint, base, "fixed", h, args.end_time, args.shape, args.threads)
        slide, s2 = fitted_acceleration(args.matpoint, base, "slip", h, args.end_time, args.shape, args.threads)
        wall = s1["wall_time_seconds"] + s2["wall_time_seconds"]
        print(f"| {h} | {0.2 / h:.0f} | {s1['particles']} | {roll:.4f} | {roll / (2 * G_SIN / 3):.4f} | "
              f"{slide:.4f} | {slide / G_SIN:.4f} | {wall:.0f} |", flush=True)


if __name__ == "__main__":
    main()
