#!/usr/bin/env python3
"""Nairn 2026 §3.1 pull test: time-averaged rms particle velocity error (in % of the end velocity
10 r) versus the FMPM order k for the new (incremental) and the old (combined) boundary method,
and FLIP, for one basis and wall depth.

Usage: python3 examples/fmpm-pull-test/sweep.py [MATPOINT] [--shape cpdi1] [--depth 0.25]
       [--orders 1,2,3,4,6,8,10,12] [--density 1] [--threads 1]
Prints a Markdown table and, last, the ratio FLIP / FMPM(k) for the largest k. --density sets the
ratio V_end / c = 0.1 sqrt(density) (0.0625: 0.025, the paper's regime, README.md).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402


def end_velocity(spec):
    """V_end = 10 r, r the initial stretching rate of the bar (X in [-10, 10])."""
    return 10 * spec["bodies"][0]["velocity_gradient"][0][0]


def error(matpoint, base, shape, depth, transfer, threads, density):
    spec = variant(base, solver=dict(transfer, shape=shape),
                   output={"every_steps": 1, "particles": False, "plots": False})
    spec["materials"][0]["density"] = density
    for wall in spec["boundary_conditions"]:
        wall["depth"] = depth
    result = run_spec(matpoint, spec, threads)
    if not result.ok:
        return float("nan")
    values = result.column("rms_velocity_change")[1:]
    return 100.0 * sum(values) / len(values) / end_velocity(spec)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--shape", default="cpdi1")
    parser.add_argument("--depth", type=float, default=0.25)
    parser.add_argument("--orders", default="1,2,3,4,6,8,10,12")
    parser.add_argument("--density", type=float, default=1.0)
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    base = load_input(HERE)
    flip = error(args.matpoint, base, args.shape, args.depth, {"transfer": "flip", "position_alpha": 0.5}, args.threads,
                 args.density)
    print(f"{args.shape}, wall depth {args.depth}: FLIP error {flip:.4g} %\n")
    print("| k | new (incremental) | old (combined) | FLIP / new |")
    print("|---|---|---|---|")
    last = None
    for k in [int(x) for x in args.orders.split(",")]:
        new = error(args.matpoint, base, args.shape, args.depth, {"transfer": "fmpm", "fmpm": {"order": k}},
                    args.threads, args.density)
        old = error(args.matpoint, base, args.shape, args.depth,
                    {"transfer": "fmpm", "fmpm": {"order": k, "boundary_method": "combined"}}, args.threads,
                    args.density)
        print(f"| {k} | {new:.4g} % | {old:.4g} % | {flip / new:.0f} |", flush=True)
        last = (k, new)
    print(f"\nFLIP / FMPM({last[0]}) = {flip / last[1]:.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
