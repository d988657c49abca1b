#!/usr/bin/env python3
"""Nairn 2026 §3.2.1 shock wave (single material): plateau stress, front position and the
column-averaged -sigma_xx profile for FLIP and FMPM(k), compared with Rankine-Hugoniot and with
FMPM(4).

Usage: /usr/bin/python3 examples/shock-interface/sweep.py [MATPOINT] [--orders 1,2,4,6,8,16]
       [--out out/shock-sweep] [--threads 2] [--courant C]
Without --courant the input's dt (6.76 ns) is used; --courant C replaces it with C h / C0.
Prints a Markdown table; writes profiles.png (needs matplotlib) and profiles.csv into --out.
Reads the last particles_*.vtu of each run with meshio.
"""
import argparse
import glob
import json
import os
import re
import subprocess

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RHO0, C0, S, UP = 8870.0, 4600.0, 1.44, 1840.0
US = C0 + S * UP
P_HUGONIOT = RHO0 * US * UP  # 118.33 GPa
COLUMN = 0.25e-3


def load_input():
    text = open(os.path.join(HERE, "input.json")).read()
    return json.loads(re.sub(r"^\s*//.*$", "", text, flags=re.MULTILINE))


def run(matpoint, base, label, solver, out_root, threads):
    spec = json.loads(json.dumps(base))
    spec["solver"].pop("fmpm", None)
    spec["solver"].update(solver)
    spec["output"] = {"particles": True, "plots": False, "fields": ["stress"]}
    out = os.path.join(out_root, label)
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "input.json")
    json.dump(spec, open(path, "w"), indent=1)
    proc = subprocess.run([matpoint, "run", path, "--out", out, "--quiet", "--threads", str(threads)],
                          capture_output=True, text=True)
    summary = json.load(open(os.path.join(out, "summary.json")))
    if proc.returncode != 0:
        return None, summary
    last = sorted(glob.glob(os.path.join(out, "particles_*.vtu")))[-1]
    mesh = meshio.read(last)
    x = mesh.points[:, 0]
    sxx = mesh.point_data["stress"][:, 0]
    return (x, -sxx, summary["time_reached"]), summary


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
    args = parser.parse_args()
    base = load_input()
    if args.courant is not None:
        base["solver"].pop("dt")
        base["solver"]["courant"] = args.courant
    runs = {"FLIP": {"transfer": "flip", "position_alpha": 0.5}}
    for k in [int(k) for k in args.orders.split(",")]:
        runs[f"FMPM({k})"] = {"transfer": "fmpm", "fmpm": {"order": k}}
    results = {}
    for label, solver in runs.items():
        data, summary = run(args.matpoint, base, label.replace("(", "").replace(")", ""), solver, args.out,
                            args.threads)
        if data is None:
            print(f"{label}: failed: {summary.get('message')}")
            continue
        x, p, t = data
        prof = profile(x, p)
        results[label] = (prof, plateau(p), t, summary["wall_time_seconds"])
    ref = results.get("FMPM(4)")
    print(f"Rankine-Hugoniot: U_s = {US:.1f} m/s, plateau {P_HUGONIOT / 1e9:.2f} GPa\n")
    print("| run | plateau (GPa) | vs 118.33 | front (mm) | exact front (mm) | peak / plateau | "
          "max column diff to FMPM(4), behind the front | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|")
    for label, (prof, pl, t, wall) in results.items():
        xf = front(prof, 0.5 * pl)
        exact = 0.05 - US * t
        diff = ""
        if ref is not None:
            behind = np.arange(200) * COLUMN > front(ref[0], 0.5 * ref[1]) + 1e-3
            diff = f"{100 * np.abs(prof[behind] - ref[0][behind]).max() / ref[1]:.2f} %"
        print(f"| {label} | {pl / 1e9:.2f} | {100 * (pl / P_HUGONIOT - 1):+.2f} % | {1e3 * xf:.2f} | "
              f"{1e3 * exact:.2f} | {prof.max() / pl:.3f} | {diff} | {wall:.1f} |")
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
