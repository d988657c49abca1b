#!/usr/bin/env python3
"""Nairn 2026 §3.2.2 two disks with friction: energy (kinetic + strain + friction work) lost at
0.16 ms for FLIP and FMPM(k) at mu = 0, 0.3, 0.6, the loss versus k at mu = 0.3 (Fig. 9), and the
largest distance between the FMPM(4) and FLIP centre-of-mass trajectories (Fig. 8).

Usage: python3 examples/two-disks-contact/sweep.py [MATPOINT] [--cell 3.3333333333e-4] [--jobs N]
       [--orders 1,2,3,4,6,8,10] [--mus 0,0.3,0.6] [--separation CELLS] [--normals NAME]
Prints Markdown tables. The paper's cell is 1/3 mm (the default); input.json's 1 mm is the CI size.
"""
import argparse
import concurrent.futures
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402


def case(base, cell, transfer, mu, separation=None, normals=None):
    spec = variant(base, solver=transfer, output={"every_time": 4e-6, "particles": False, "plots": False})
    spec["grid"]["cell_size"] = cell
    spec["contact"] = {"law": "coulomb", "friction": mu} if mu > 0 else {"law": "frictionless"}
    spec["contact"]["normals"] = normals or base["contact"].get("normals", "average")
    if separation is not None:
        spec["contact"]["separation"] = separation
    spec.pop("checks", None)
    return spec


def run(matpoint, spec):
    result = run_spec(matpoint, spec)
    summary, rows = result.summary, result.history
    e0 = summary["initial"]["total_energy"]
    final = summary["final"]
    loss = 1 - (final["total_energy"] + final.get("friction_work", 0.0)) / e0
    com = [[(float(r[f"body{b}_com_x"]), float(r[f"body{b}_com_y"])) for b in (0, 1)] for r in rows]
    return {"loss": loss, "friction": final.get("friction_work", 0.0) / e0, "com": com,
            "ok": result.ok, "time": summary["step_wall_seconds"]}


def distance(a, b):
    return max(math.dist(p, q) for ra, rb in zip(a, b) for p, q in zip(ra, rb))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--cell", type=float, default=1e-3 / 3)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--orders", default="1,2,3,4,6,8,10")
    parser.add_argument("--mus", default="0,0.3,0.6")
    parser.add_argument("--separation", type=float, default=None,
                        help="contact.separation (position criterion, cells); default: approach test only")
    parser.add_argument("--normals", default=None,
                        help="contact.normals (average, mass_gradient, logistic_regression); default: the input's")
    parser.add_argument("--check", action="store_true",
                        help="compare with Nairn 2026 Figs. 9A, 9B (1/3 mm cells): exit 1 unless FLIP and FMPM(4) lose "
                             "< 2 %% at every mu and FMPM(1) loses 18.7 %% +/- 1 point at mu = 0.3")
    args = parser.parse_args()
    base = load_input(HERE)
    flip = {"transfer": "flip"}
    fmpm = lambda k: {"transfer": "fmpm", "fmpm": {"order": k}}
    mus = [float(m) for m in args.mus.split(",")]
    cases = {}
    for mu in mus:
        cases[("FLIP", mu)] = case(base, args.cell, flip, mu, args.separation, args.normals)
        cases[("FMPM(4)", mu)] = case(base, args.cell, fmpm(4), mu, args.separation, args.normals)
    for k in (int(k) for k in args.orders.split(",") if k):
        cases.setdefault((f"FMPM({k})", 0.3), case(base, args.cell, fmpm(k), 0.3, args.separation, args.normals))
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = {key: pool.submit(run, args.matpoint, spec) for key, spec in cases.items()}
        results = {key: f.result() for key, f in futures.items()}
    note = lambda r: "" if r["ok"] else " (stopped: numerical failure)"
    print(f"cell = {args.cell * 1e3:.4g} mm, separation = {args.separation}, normals = {args.normals}\n")
    print("| mu | FLIP loss | FMPM(4) loss | FLIP friction work | FMPM(4) friction work | max COM distance FMPM(4) - FLIP |")
    print("|---|---|---|---|---|---|")
    for mu in mus:
        a, b = results[("FLIP", mu)], results[("FMPM(4)", mu)]
        print(f"| {mu} | {100 * a['loss']:.2f} %{note(a)} | {100 * b['loss']:.2f} %{note(b)} | "
              f"{100 * a['friction']:.2f} % | {100 * b['friction']:.2f} % | {1e3 * distance(a['com'], b['com']):.3f} mm |")
    print("\n| mu = 0.3 | energy lost | step time / FLIP |")
    print("|---|---|---|")
    flip_time = results[("FLIP", 0.3)]["time"] if ("FLIP", 0.3) in results else None
    keys = [("FLIP", 0.3)] + sorted((k for k in results if k[1] == 0.3 and k[0] != "FLIP"),
                                    key=lambda k: int(k[0][5:-1]))
    for key in keys:
        if key not in results:
            continue
        r = results[key]
        ratio = f"{r['time'] / flip_time:.2f}" if flip_time else "-"
        print(f"| {key[0]} | {100 * r['loss']:.2f} %{note(r)} | {ratio} |")
    return check(results, mus) if args.check else 0


def check(results, mus):
    """Nairn 2026 Fig. 9A: FLIP and FMPM(4) lose < 2 % at every mu; Fig. 9B: FMPM(1) 18.7 % at mu = 0.3.
    The 1 point allowed on FMPM(1) is the reading of a bar chart, not a fit to our runs."""
    ok = True
    print("\nchecks against Nairn 2026 (1/3 mm cells):")
    for mu in mus:
        for method in ("FLIP", "FMPM(4)"):
            r = results[(method, mu)]
            passed = r["ok"] and 0 <= r["loss"] < 0.02
            ok = ok and passed
            print(f"  {'PASS' if passed else 'FAIL'} {method}, mu = {mu}: loss {100 * r['loss']:.2f} % < 2 % (Fig. 9A)")
    if ("FMPM(1)", 0.3) in results:
        r = results[("FMPM(1)", 0.3)]
        passed = r["ok"] and abs(r["loss"] - 0.187) <= 0.01
        ok = ok and passed
        print(f"  {'PASS' if passed else 'FAIL'} FMPM(1), mu = 0.3: loss {100 * r['loss']:.2f} % = 18.7 +/- 1 % (Fig. 9B)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
