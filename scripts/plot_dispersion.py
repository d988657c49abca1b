#!/usr/bin/env python3
"""Draw the plots of `matpoint dispersion`: plot_dispersion.py DIR

Reads DIR/dispersion.csv (one curve per particles-per-cell N) and DIR/dispersion_bounds.csv, and writes
DIR/plots/dispersion_amplitude.png (|M(theta)| with the stability line |M| = 1),
DIR/plots/dispersion_phase_speed.png (Re(omega) / (C F0 k)) and DIR/plots/dispersion_growth.png
(ln max|lambda| per step). Each image is saved under a temporary name and renamed, so a plot is either
whole or absent. Run by `matpoint dispersion`; needs python3-matplotlib.
"""
import csv
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:
    sys.exit(f"plot_dispersion.py: {missing} (install python3-matplotlib and python3-numpy, "
             f"or run scripts/setup.sh; {sys.executable} is the interpreter in use)")


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path} has no data rows")
    return rows


def curves_by_n(rows):
    curves = {}
    for row in rows:
        curves.setdefault(int(row["particles_per_cell"]), []).append(row)
    return {n: {key: np.array([float(r[key]) for r in rs]) for key in rs[0] if key != "relation"}
            for n, rs in sorted(curves.items())}


def save(fig, plots, name):
    final = os.path.join(plots, name)
    temporary = final[:-4] + ".partial.png"  # the extension tells matplotlib the format
    fig.savefig(temporary, dpi=120)
    plt.close(fig)
    os.replace(temporary, final)


def plot_quantity(curves, key, ylabel, title, plots, name, line=None):
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for n, c in curves.items():
        ax.plot(c["theta"] / np.pi, np.abs(c[key]) if key == "m" else c[key], label=f"$N_p^e$ = {n}")
    if line is not None:
        ax.axhline(line, color="k", lw=0.8, ls="--")
    ax.set_xlabel(r"$\theta / \pi = k h / \pi$")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(loc="best")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, name)


def main(argv):
    if len(argv) != 2:
        print("usage: plot_dispersion.py DIR", file=sys.stderr)
        return 2
    directory = argv[1]
    rows = read_rows(os.path.join(directory, "dispersion.csv"))
    relation, courant = rows[0]["relation"], float(rows[0]["courant"])
    curves = curves_by_n(rows)
    bounds_file = os.path.join(directory, "dispersion_bounds.csv")
    bounds = read_rows(bounds_file) if os.path.exists(bounds_file) else []
    tight = ", ".join(f"{int(b['particles_per_cell'])}: {float(b['tight']):.5f}" for b in bounds)
    source = "Gong 2015 ch. 7, " + ("(7.29) with the square kept" if relation == "corrected"
                                    else "Bloch analysis of (7.15)-(7.16)")
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    plot_quantity(curves, "m", r"$|M(\theta)|$  (stable where $\leq 1$)",
                  f"{source}, CFL = {courant:g}" + (f"\ntight CFL bounds (N: bound) {tight}" if tight else ""),
                  plots, "dispersion_amplitude.png", line=1.0)
    plot_quantity(curves, "phase_speed_ratio", r"phase speed ratio Re$(\omega) / (C F_0 k)$",
                  f"{source}, CFL = {courant:g}", plots, "dispersion_phase_speed.png", line=1.0)
    plot_quantity(curves, "growth_per_step", r"growth per step  $\ln \max|\lambda|$",
                  f"{source}, CFL = {courant:g}", plots, "dispersion_growth.png", line=0.0)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except Exception as error:  # a clear one-line message instead of a traceback
        print(f"plot_dispersion.py: {type(error).__name__}: {error}", file=sys.stderr)
        sys.exit(1)
