#!/usr/bin/env python3
"""Nairn 2026 §3.2.1 shock wave: plateau stress, front position and the column-averaged -sigma_xx
profile for FLIP and FMPM(k), compared with Rankine-Hugoniot and with the single-material FMPM(4);
with --interface, the bar split at x = 40 mm into two materials joined by stick or frictionless
contact (Net and Evolving increments, Fig. 5).

Usage: /usr/bin/python3 examples/shock-interface/sweep.py [MATPOINT] [--orders 1,2,4,6,8,16]
       [--out out/shock-sweep] [--threads 2] [--courant C] [--interface] [--normals logistic_regression]
Without --courant the input's dt (6.76 ns) is used; --courant C replaces it with C h / C0.
Prints a Markdown table; writes profiles.png (needs matplotlib) and profiles.csv into --out.
Reads the last particles_*.vtu of each run with meshio.
"""
import argparse
import glob
import os
import sys

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from example_tools import load_input, run_spec, variant  # noqa: E402

RHO0, C0, S, UP = 8870.0, 4600.0, 1.44, 1840.0
US = C0 + S * UP
P_HUGONIOT = RHO0 * US * UP  # 118.33 GPa
COLUMN = 0.25e-3
INTERFACE = 0.04  # the paper's split of the bar into two materials (§3.2.1)


def split_bar(base, law, method, normals):
    """The paper's two-material bar: x < 40 mm and x > 40 mm as separate bodies of two identical
    materials, joined by contact `law` with the FMPM increment `method`."""
    spec = variant(base)
    nickel = dict(spec["materials"][0])
    spec["materials"].append(dict(nickel, name="nickel-right"))
    bar = spec["bodies"][0]
    left = dict(bar, name="left", shape=dict(bar["shape"], max=[INTERFACE, bar["shape"]["max"][1]]))
    right = dict(bar, name="right", material="nickel-right",
                 shape=dict(bar["shape"], min=[INTERFACE, bar["shape"]["min"][1]]))
    spec["bodies"] = [left, right]
    spec["contact"] = {"law": law, "fmpm_method": method, "normals": normals}
    return spec


def run(matpoint, spec, label, out_root, threads):
    """The last state's particle x and -sigma_xx, and the summary; None when the run failed."""
    spec = variant(spec, output={"particles": True, "plots": False, "fields": ["stress"]})
    result = run_spec(matpoint, spec, threads, out=os.path.join(out_root, label))
    if not result.ok:
        return None, result.summary
    mesh = meshio.read(sorted(glob.glob(os.path.join(result.out, "particles_*.vtu")))[-1])
    return (mesh.points[:, 0], -mesh.point_data["stress"][:, 0], result.summary["time_reached"]), result.summary


def plateau(p):
    top = p[p >= 0.5 * p.max()]
    return np.sort(top)[len(top) // 2]  # the rule of the measure shock_plateau_stress


def profile(x, p):
    bins = np.floor(x / COLUMN).astype(int)
    out = np.zeros(200)
    for b in range(200):
        sel = bins == b
        out[b] = p[sel].mean() if sel.any() else 0.0
    return out


def front(prof, level):
    b = int(np.argmax(prof >= level))
    below = prof[b - 1] if b > 0 else 0.0
    return COLUMN * (b - 0.5 + (level - below) / (prof[b] - below))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("matpoint", nargs="?", default=os.path.join(HERE, "..", "..", "build", "matpoint"))
    parser.add_argument("--orders", default="1,2,4,6,8,16")
    parser.add_argument("--out", default="out/shock-sweep")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--courant", type=float, default=None)
    parser.add_argument("--interface", action="store_true",
                        help="the split bar: stick and frictionless interfaces, Net and Evolving, "
                             "against the single-material FMPM(4)")
    parser.add_argument("--normals", default="logistic_regression", help="contact.normals of the split bar")
    args = parser.parse_args()
    base = load_input(HERE)
    if args.courant is not None:
        base["solver"].pop("dt")
        base["solver"]["courant"] = args.courant
    orders = [int(k) for k in args.orders.split(",")]
    fmpm = lambda k: {"transfer": "fmpm", "fmpm": {"order": k}}  # noqa: E731
    runs = {"FLIP": variant(base, solver={"transfer": "flip", "position_alpha": 0.5})}
    if args.interface:
        runs["FMPM(4)"] = variant(base, solver=fmpm(4))
        for law, method in (("stick", "net"), ("frictionless", "net"), ("frictionless", "evolving")):
            for k in orders:
                name = f"{law} {method} FMPM({k})"
                runs[name] = variant(split_bar(base, law, method, args.normals), solver=fmpm(k))
        runs["frictionless FLIP"] = variant(split_bar(base, "frictionless", "net", args.normals),
                                            solver={"transfer": "flip", "position_alpha": 0.5})
    else:
        for k in orders:
            runs[f"FMPM({k})"] = variant(base, solver=fmpm(k))
    results = {}
    for label, spec in runs.items():
        data, summary = run(args.matpoint, spec, label.replace("(", "").replace(")", "").replace(" ", "-"),
                            args.out, args.threads)
        if data is None:
            print(f"{label}: failed: {summary.get('message')}")
            continue
        x, p, t = data
        prof = profile(x, p)
        results[label] = (prof, plateau(p), t, summary["wall_time_seconds"])
    ref = results.get("FMPM(4)")
    print(f"Rankine-Hugoniot: U_s = {US:.1f} m/s, plateau {P_HUGONIOT / 1e9:.2f} GPa\n")
    print("| run | plateau (GPa) | vs 118.33 | front (mm) | exact front (mm) | peak / plateau | "
          "column diff to FMPM(4) behind the front: mean / max | max within 1.5 mm of x = 40 mm | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    x_columns = (np.arange(200) + 0.5) * COLUMN
    for label, (prof, pl, t, wall) in results.items():
        xf = front(prof, 0.5 * pl)
        exact = 0.05 - US * t
        diff = near = ""
        if ref is not None:
            behind = x_columns > front(ref[0], 0.5 * ref[1]) + 1e-3
            behind &= x_columns < 0.0455  # left of the wall's final position
            d = 100 * (prof - ref[0]) / ref[1]
            diff = f"{d[behind].mean():+.2f} / {np.abs(d[behind]).max():.2f} %"
            close = behind & (np.abs(x_columns - INTERFACE) < 1.5e-3)
            near = f"{np.abs(d[close]).max():.2f} %"
        print(f"| {label} | {pl / 1e9:.2f} | {100 * (pl / P_HUGONIOT - 1):+.2f} % | {1e3 * xf:.2f} | "
              f"{1e3 * exact:.2f} | {prof.max() / pl:.3f} | {diff} | {near} | {wall:.1f} |")
    centres = (np.arange(200) + 0.5) * COLUMN * 1e3
    with open(os.path.join(args.out, "profiles.csv"), "w") as f:
        f.write("x_mm," + ",".join(results) + "\n")
        for b in range(200):
            f.write(f"{centres[b]:.4f}," + ",".join(f"{results[k][0][b]:.6e}" for k in results) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(8, 4))
        for label, (prof, *_rest) in results.items():
            ax.plot(centres, prof / 1e9, label=label, lw=1)
        ax.axhline(P_HUGONIOT / 1e9, color="k", ls="--", lw=0.8, label="Rankine-Hugoniot")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("-sigma_xx (GPa), column average")
        ax.set_xlim(25, 50)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "profiles.png"), dpi=120)
    except ImportError:
        pass


if __name__ == "__main__":
    main()
