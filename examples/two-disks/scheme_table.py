#!/usr/bin/env python3
"""Runs two-disks with every update scheme, velocity transfer and basis and prints the energy table.

Usage: python3 examples/two-disks/scheme_table.py [MATPOINT] [--end-time T]
The table (Markdown) goes to standard output; each run's output folder is a temporary directory.
Columns: the signed extreme of (E(t) - E(0)) / E(0) over all output times, the final value, the
smallest det F, and the run status (exit code 3 = stopped by a numerical guard).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMES = ["usl", "usf", "musl", "usavg"]
TRANSFERS = [  # (label, solver keys)
    ("FLIP alpha=1", {"transfer": "flip", "position_alpha": 1.0}),
    ("FLIP alpha=1/2", {"transfer": "flip", "position_alpha": 0.5}),
    ("blend 0.99", {"transfer": "blend", "flip_fraction": 0.99}),
    ("PIC", {"transfer": "pic"}),
]
SHAPES = ["bspline2", "linear"]


def load_input():
    with open(os.path.join(HERE, "input.json")) as f:
        text = f.read()
    text = re.sub(r"^\s*//.*$", "", text, flags=re.MULTILINE)  # the example uses whole-line comments only
    return json.loads(text)


def run_case(matpoint, base, shape, scheme, transfer_keys, end_time):
    spec = json.loads(json.dumps(base))
    solver = spec["solver"]
    solver.update({"scheme": scheme, "shape": shape, "end_time": end_time})
    for key in ("transfer", "position_alpha", "flip_fraction"):
        solver.pop(key, None)
    solver.update(transfer_keys)
    spec["checks"] = []
    spec["output"] = {"every_time": 0.05, "particles": False, "plots": False}
    with tempfile.TemporaryDirectory() as out:
        path = os.path.join(out, "input.json")
        with open(path, "w") as f:
            json.dump(spec, f)
        proc = subprocess.run([matpoint, "run", path, "--out", out, "--quiet", "--threads", "1"],
                              capture_output=True, text=True)
        rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    e0 = float(rows[0]["total_energy"])
    errors = [(float(r["total_energy"]) - e0) / e0 for r in rows]
    extreme = max(errors, key=abs)
    min_j = min(float(r["min_jacobian"]) for r in rows)
    status = "ok" if proc.returncode == 0 else f"exit {proc.returncode} at t={float(rows[-1]['time']):.2f}"
    return extreme, errors[-1], min_j, status


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--end-time", type=float, default=3.0)
    args = parser.parse_args()
    base = load_input()
    print("| basis | scheme | transfer | extreme energy error | final energy error | min det F | status |")
    print("|---|---|---|---|---|---|---|")
    for shape in SHAPES:
        for scheme in SCHEMES:
            for label, keys in TRANSFERS:
                extreme, final, min_j, status = run_case(args.matpoint, base, shape, scheme, keys, args.end_time)
                print(f"| {shape} | {scheme.upper()} | {label} | {100 * extreme:+.3f} % | {100 * final:+.3f} % "
                      f"| {min_j:.3f} | {status} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
