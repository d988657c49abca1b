#!/usr/bin/env python3
"""Draw the plots of a matpoint output folder: plot_history.py DIR

Writes DIR/plots/energy.png (energies and the relative energy-balance drift), DIR/plots/momentum.png,
DIR/plots/probes.png when the input has output.probes (displacement, velocity and stress of each
probed particle) and, for 2-D runs, DIR/plots/final_state.png (the last particles_NNNNNN.vtu
coloured by speed).
Each image is saved under a temporary name and renamed, so a plot is either whole or absent.
Run by `matpoint run` at the end of a run and by `matpoint plot DIR`; needs python3-matplotlib
(and python3-meshio for final_state.png, skipped without it). MATPOINT_PLOT_DPI sets the
resolution (default 120; scripts/verification_table.py --figures uses 50 for the examples' READMEs).
"""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:
    sys.exit(f"plot_history.py: {missing} (install python3-matplotlib and python3-numpy, "
             f"or run scripts/setup.sh; {sys.executable} is the interpreter in use)")


def read_history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        raise ValueError(f"{path} has no data rows")
    header = rows[0]
    data = np.array([[float(v) for v in row] for row in rows[1:] if row], dtype=float)
    return {name: data[:, i] for i, name in enumerate(header)}


def save(fig, plots, name):
    final = os.path.join(plots, name)
    temporary = final[:-4] + ".partial.png"  # the extension tells matplotlib the format
    fig.savefig(temporary, dpi=int(os.environ.get("MATPOINT_PLOT_DPI", "120")))
    plt.close(fig)
    os.replace(temporary, final)


def plot_energy(h, title, plots):
    t = h["time"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    top.plot(t, h["kinetic_energy"], label="kinetic")
    top.plot(t, h["strain_energy"], label="strain")
    top.plot(t, h["total_energy"], label="total", lw=2, color="k")
    if np.any(h.get("external_work", np.zeros(1)) != 0):
        top.plot(t, h["external_work"], "--", label="external work")
        top.plot(t, h["energy_balance"], ":", label="total - external work")
    top.set_ylabel("energy")
    top.set_title(title or "energy")
    top.legend(loc="best")
    top.grid(alpha=0.3)

    # Drift of B = K + U + D - W_ext over the energy scale seen so far, max(K(0) + U(0), max |W_ext|):
    # the energy the problem was given or has received (the measure max_relative_energy_error uses
    # the same scale over the whole run). A block dropped from rest has K(0) + U(0) = 0 and is
    # measured against the work gravity has done.
    balance = h["energy_balance"]
    external = np.abs(h.get("external_work", np.zeros_like(balance)))
    scale = np.maximum(h["total_energy"][0], np.maximum.accumulate(external))
    with np.errstate(divide="ignore", invalid="ignore"):
        drift = np.where(scale > 0, (balance - balance[0]) / np.where(scale > 0, scale, 1.0), 0.0)
    bottom.plot(t, 100 * drift, color="tab:red")
    bottom.set_ylabel("energy balance drift\n(% of energy scale)")
    bottom.set_xlabel("time")
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "energy.png")


def plot_momentum(h, title, plots):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for axis in "xyz":
        if f"momentum_{axis}" in h:
            ax.plot(h["time"], h[f"momentum_{axis}"], label=f"momentum {axis}")
    ax.set_xlabel("time")
    ax.set_ylabel("linear momentum")
    ax.set_title(title or "momentum")
    ax.legend(loc="best")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "momentum.png")


def probe_names(h):
    """Probe names in column order, from the probe_NAME_J columns of history.csv."""
    return [column[len("probe_"):-len("_J")] for column in h if column.startswith("probe_") and column.endswith("_J")]


def plot_probes(h, title, plots):
    names = probe_names(h)
    if not names:
        return
    rows = [("displacement", ["ux", "uy", "uz"]), ("velocity", ["vx", "vy", "vz"]),
            ("Cauchy stress", ["sxx", "syy", "szz", "sxy", "sxz", "syz"])]
    fig, axes = plt.subplots(len(rows), 1, figsize=(8, 9), sharex=True)
    for ax, (label, components) in zip(axes, rows):
        for name in names:
            for component in components:
                if f"probe_{name}_{component}" in h:
                    ax.plot(h["time"], h[f"probe_{name}_{component}"], label=f"{name}: {component}")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    axes[0].set_title(title or "probes")
    axes[-1].set_xlabel("time")
    fig.tight_layout()
    save(fig, plots, "probes.png")


def last_vtu(directory):
    pvd = os.path.join(directory, "results.pvd")
    if not os.path.exists(pvd):
        return None
    datasets = list(ET.parse(pvd).getroot().iter("DataSet"))
    if not datasets:
        return None
    return os.path.join(directory, datasets[-1].get("file")), datasets[-1].get("timestep")


def plot_final_state(directory, title, plots):
    try:
        import meshio
    except ImportError:
        return
    last = last_vtu(directory)
    if last is None or not os.path.exists(last[0]):
        return
    vtu, time = last
    mesh = meshio.read(vtu)
    x = mesh.points
    v = mesh.point_data.get("velocity")
    fig, ax = plt.subplots(figsize=(7, 6))
    if v is None:
        ax.scatter(x[:, 0], x[:, 1], s=4)
    else:
        speed = np.linalg.norm(v, axis=1)
        dots = ax.scatter(x[:, 0], x[:, 1], c=speed, s=4, cmap="viridis")
        fig.colorbar(dots, ax=ax, label="velocity magnitude")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title(f"{title + chr(10) if title else ''}t = {float(time):.6g} ({os.path.basename(vtu)})")
    fig.tight_layout()
    save(fig, plots, "final_state.png")


def main(argv):
    if len(argv) != 2:
        print("usage: plot_history.py DIR", file=sys.stderr)
        return 2
    directory = argv[1]
    history_file = os.path.join(directory, "history.csv")
    if not os.path.exists(history_file):
        print(f"plot_history.py: {history_file} not found", file=sys.stderr)
        return 1
    summary = {}
    summary_file = os.path.join(directory, "summary.json")
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
    title = summary.get("title", "")
    h = read_history(history_file)
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    plot_energy(h, title, plots)
    plot_momentum(h, title, plots)
    plot_probes(h, title, plots)
    if "momentum_y" in h and "momentum_z" not in h:
        plot_final_state(directory, title, plots)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except Exception as error:  # a clear one-line message instead of a traceback
        print(f"plot_history.py: {type(error).__name__}: {error}", file=sys.stderr)
        sys.exit(1)
