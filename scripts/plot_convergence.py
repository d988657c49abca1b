#!/usr/bin/env python3
"""Log-log convergence plot of a `matpoint verify` case: plot_convergence.py CSV [TITLE].

Reads the CSV written by `matpoint verify` (h, cells, finished, displacement, stress, density,
velocity) and writes the PNG beside it (same name, .png): one line per error norm, as in Gong 2015
Figs 4.7-4.10, with the least-squares order of the finished runs in the legend.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def slope(h, e):
    pts = [(math.log(a), math.log(b)) for a, b in zip(h, e) if a > 0 and b > 0]
    if len(pts) < 2:
        return float("nan")
    n = len(pts)
    sx = sum(p[0] for p in pts)
    sy = sum(p[1] for p in pts)
    sxx = sum(p[0] ** 2 for p in pts)
    sxy = sum(p[0] * p[1] for p in pts)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def main():
    path = sys.argv[1]
    title = sys.argv[2] if len(sys.argv) > 2 else path
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["finished"] == "1"]
    h = [float(r["h"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 5))
    for q, marker in (("stress", "o"), ("density", "s"), ("velocity", "^"), ("displacement", "v"),
                      ("grid_velocity", "D")):
        e = [float(r[q]) for r in rows]
        ax.loglog(h, e, marker=marker, label=f"{q} (order {slope(h, e):.2f})")
    if h:
        ref = [h[0] ** 2 * (x / h[0]) ** 2 for x in h]
        ax.loglog(h, [r / ref[0] * 1e-6 for r in ref], "k:", label="slope 2")
    ax.set_xlabel("h")
    ax.set_ylabel("L2 error at T (particle quadrature)")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path[:-4] + ".png", dpi=110)


if __name__ == "__main__":
    main()
