#!/usr/bin/env python3
"""Nairn 2026 §3.4 two-block impact: energy loss, average FMPM order and run time relative to FLIP
for FLIP, FMPM(2), FMPM(20) and dynamic FMPM(20) over a range of convergence limits.

Usage: python3 examples/fmpm-two-blocks/sweep.py [MATPOINT] [--limits 0.1,0.01,...] [--threads N]
Prints a Markdown table. One thread by default, so the times compare.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402


def run(matpoint, base, transfer, threads):
    spec = variant(base, solver=transfer, output={"every_time": 1e-5, "particles": False, "plots": False})
    result = run_spec(matpoint, spec, threads)
    summary = result.summary
    initial, final = summary["initial"]["total_energy"], summary["final"]["total_energy"]
    return {"loss": 1 - final / initial, "time": summary["step_wall_seconds"],
            "order": summary.get("fmpm_average_order", 0.0), "ok": result.ok}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--limits", default="0.1,0.03,0.01,0.003,0.0015,0.001,0.0001")
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    base = load_input(HERE)
    cases = [("FLIP (alpha 1/2)", {"transfer": "flip", "position_alpha": 0.5}),
             ("FMPM(2)", {"transfer": "fmpm", "fmpm": {"order": 2}}),
             ("FMPM(4)", {"transfer": "fmpm", "fmpm": {"order": 4}}),
             ("FMPM(20)", {"transfer": "fmpm", "fmpm": {"order": 20}})]
    for measure in ("means", "changes"):
        for limit in args.limits.split(","):
            cases.append((f"dynamic FMPM(20), {measure} < {limit}",
                          {"transfer": "fmpm",
                           "fmpm": {"order": 20, "dynamic": {"measure": measure, "limit": float(limit)}}}))
    flip_time = None
    print("| method | energy lost | average order | time / FLIP |")
    print("|---|---|---|---|")
    for name, transfer in cases:
        r = run(args.matpoint, base, transfer, args.threads)
        flip_time = flip_time or r["time"]
        status = "" if r["ok"] else " (stopped: numerical failure)"
        order = f"{r['order']:.2f}" if r["order"] else "-"
        print(f"| {name}{status} | {100 * r['loss']:.3f} % | {order} | {r['time'] / flip_time:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
