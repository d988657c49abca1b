#!/usr/bin/env python3
"""Fits Nairn 2026 eq. (3), relative time = 1 + phi (k - 1) F, to measured run times of FMPM(k).

Usage: python3 bench/fmpm_cost_model.py [MATPOINT] [--input examples/fmpm-two-blocks/input.json]
       [--orders 1,2,4,8,12,16,20] [--end-time 2e-4] [--repeat 3] [--threads 1]
Each order runs --repeat times (best time kept) with USL (phi = 1), fixed order (no dynamic stop).
Prints the table, F (least squares through relative time 1 at k = 1) and R^2.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def step_time(matpoint, spec, threads):
    with tempfile.TemporaryDirectory() as out:
        path = os.path.join(out, "input.json")
        json.dump(spec, open(path, "w"))
        subprocess.run([matpoint, "run", path, "--out", out, "--quiet", "--threads", str(threads)], check=True,
                       capture_output=True)
        return json.load(open(os.path.join(out, "summary.json")))["step_wall_seconds"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(ROOT, "build", "matpoint"))
    parser.add_argument("--input", default=os.path.join(ROOT, "examples", "fmpm-two-blocks", "input.json"))
    parser.add_argument("--orders", default="1,2,4,8,12,16,20")
    parser.add_argument("--end-time", type=float, default=2e-4)
    parser.add_argument("--max-steps", type=int, default=0)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    base = json.loads(re.sub(r"^\s*//.*$", "", open(args.input).read(), flags=re.MULTILINE))
    base["solver"].update({"scheme": "usl", "transfer": "fmpm", "end_time": args.end_time})
    if args.max_steps:
        base["solver"]["max_steps"] = args.max_steps
    base["output"] = {"particles": False, "plots": False}
    base.pop("checks", None)
    orders = [int(k) for k in args.orders.split(",")]
    times = {}
    for k in orders:
        spec = json.loads(json.dumps(base))
        spec["solver"]["fmpm"] = {"order": k}
        times[k] = min(step_time(args.matpoint, spec, args.threads) for _ in range(args.repeat))
    t1 = times[orders[0]] if orders[0] == 1 else None
    if t1 is None:
        sys.exit("--orders must start with 1")
    xs = [k - 1 for k in orders]
    ys = [times[k] / t1 - 1 for k in orders]
    f = sum(x * y for x, y in zip(xs, ys)) / sum(x * x for x in xs)
    mean = sum(y + 1 for y in ys) / len(ys)
    ss_res = sum((y - f * x) ** 2 for x, y in zip(xs, ys))
    ss_tot = sum((y + 1 - mean) ** 2 for y in ys)
    print("| k | step time (s) | relative | fit 1 + (k - 1) F |")
    print("|---|---|---|---|")
    for k, x, y in zip(orders, xs, ys):
        print(f"| {k} | {times[k]:.3f} | {1 + y:.3f} | {1 + f * x:.3f} |")
    print(f"\nF = {f:.3f}, R^2 = {1 - ss_res / ss_tot:.4f}  (Nairn 2026: F = 0.244 on 8 processors)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
