#!/usr/bin/env python3
"""Draw the plots of a matpoint output folder: plot_history.py DIR

Writes DIR/plots/energy.png (energies and the relative energy-balance drift), DIR/plots/momentum.png,
DIR/plots/probes.png when the input has output.probes (displacement, velocity and stress of each
probed particle: one colour per probe, one line style per component), DIR/plots/newton.png for
implicit runs (Newton iterations, final residual norm, step cuts and dt per recorded step),
DIR/plots/temperature.png for runs with coupled heat (largest and mean particle temperature; U + K
and the change of the free energy A) and, for
2-D and 3-D runs,
DIR/plots/final_state.png (the last particles_NNNNNN.vtu coloured by speed; in 3-D its x-y and
x-z projections). Axes carry the units of the input's optional `units` block.
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


def axis_label(quantity, units):
    """'energy [J]': the quantity with the unit the input's optional `units` block names for it
    (docs/input.md#units); derived units are built from length, time and mass; no unit, no brackets."""
    length, time, mass = units.get("length"), units.get("time"), units.get("mass")
    derived = {
        "time": time,
        "time step": time,
        "length": length,
        "displacement": length,
        "velocity": f"{length}/{time}" if length and time else None,
        "energy": units.get("energy") or (f"{mass}·{length}²/{time}²" if mass and length and time else None),
        "linear momentum": f"{mass}·{length}/{time}" if mass and length and time else None,
        "stress": units.get("stress") or (f"{mass}/({length}·{time}²)" if mass and length and time else None),
    }
    unit = derived.get(quantity.split(" ")[-1] if quantity.startswith("Cauchy") else quantity)
    return f"{quantity} [{unit}]" if unit else quantity


def short_title(text, width=70):
    """A title that fits the figure: wrapped at `width` characters, at most two lines."""
    import textwrap
    lines = textwrap.wrap(text, width) or [""]
    return "\n".join(lines[:2]) + ("..." if len(lines) > 2 else "")


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


def plot_energy(h, title, plots, units):
    t = h["time"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    top.plot(t, h["kinetic_energy"], label="kinetic")
    top.plot(t, h["strain_energy"], label="strain")
    top.plot(t, h["total_energy"], label="total", lw=2, color="k")
    dissipated = [(name, label) for name, label in (("friction_work", "friction work"),
                                                     ("plastic_work", "plastic work"))
                  if np.any(h.get(name, np.zeros(1)) != 0)]
    for name, label in dissipated:
        top.plot(t, h[name], "-.", label=label)
    if np.any(h.get("external_work", np.zeros(1)) != 0):
        top.plot(t, h["external_work"], "--", label="external work")
    if dissipated or np.any(h.get("external_work", np.zeros(1)) != 0):
        top.plot(t, h["energy_balance"], ":", label="total + dissipated - external work")
    top.set_ylabel(axis_label("energy", units))
    top.set_title(short_title(title) or "energy")
    top.legend(loc="best")
    top.grid(alpha=0.3)

    # Drift of B = K + U + D - W_ext (D: friction and plastic work) over the energy scale seen so far, max(K(0) + U(0), max |W_ext|):
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
    bottom.set_xlabel(axis_label("time", units))
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "energy.png")


def plot_momentum(h, title, plots, units):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for axis in "xyz":
        if f"momentum_{axis}" in h:
            ax.plot(h["time"], h[f"momentum_{axis}"], label=f"momentum {axis}")
    ax.set_xlabel(axis_label("time", units))
    ax.set_ylabel(axis_label("linear momentum", units))
    ax.set_title(short_title(title) or "momentum")
    ax.legend(loc="best")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "momentum.png")


def plot_newton(h, title, plots, units):
    """Implicit runs: Newton's work per step (history.csv's newton_* columns) and the time step."""
    if "newton_iterations" not in h:
        return
    rows = [k for k, step in enumerate(h["step"]) if step > 0]  # the first row is the initial state
    if not rows:
        return
    time = [h["time"][k] for k in rows]
    # A row holds the iterations of every step since the previous row (docs/output.md): per step,
    # they are divided by that count (1 when every step is recorded).
    per_step = [
        h["newton_iterations"][k] / max(h["step"][k] - (h["step"][k - 1] if k > 0 else 0), 1) for k in rows
    ]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    top.step(time, per_step, where="post", label="Newton iterations")
    cuts = [(t, n) for t, k, n in zip(time, rows, per_step) if h["step_cuts"][k] > 0]
    if cuts:
        top.plot(*zip(*cuts), "rv", label="step cut")
    top.set_ylabel("iterations per step\n(mean since the previous row)")
    twin = top.twinx()
    twin.semilogy(time, [max(h["newton_residual"][k], 1e-300) for k in rows], "k:", label="final |R|")
    twin.set_ylabel("final residual norm")
    lines = top.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    top.legend(lines[0] + more[0], lines[1] + more[1], loc="best")
    top.set_title(short_title(title) or "Newton")
    top.grid(alpha=0.3)
    steps = [h["dt"][k] for k in rows]
    bottom.plot(time, steps, ".-")
    bottom.set_ylim(0, 1.1 * max(steps))  # from 0: a step shortened by round-off to land on end_time is no event
    bottom.set_xlabel(axis_label("time", units))
    bottom.set_ylabel(axis_label("time step", units))
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "newton.png")


def plot_temperature(h, title, plots, units):
    """Coupled heat: temperatures (top) and U + K, Delta A (bottom; Nairn 2026 Figs. 9A, 10)."""
    if "temperature_max" not in h:
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    top.plot(h["time"], h["temperature_max"], label="largest particle temperature")
    top.plot(h["time"], h["temperature_mean"], label="mean particle temperature")
    top.set_ylabel("temperature")
    top.set_title(short_title(title) or "temperature")
    top.legend(loc="best")
    top.grid(alpha=0.3)
    total = [u + k for u, k in zip(h["internal_energy"], h["kinetic_energy"])]
    bottom.plot(h["time"], total, label="U + K")
    bottom.plot(h["time"], [a - h["free_energy"][0] for a in h["free_energy"]], label="free energy change ΔA")
    bottom.set_xlabel(axis_label("time", units))
    bottom.set_ylabel(axis_label("energy", units))
    bottom.legend(loc="best")
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, plots, "temperature.png")


def probe_names(h):
    """Probe names in column order, from the probe_NAME_J columns of history.csv."""
    return [column[len("probe_"):-len("_J")] for column in h if column.startswith("probe_") and column.endswith("_J")]


# One colour per probe, one line style per component: a 3-D probe has 3 displacement and 6 stress
# components, more lines than a colour cycle has colours.
LINE_STYLES = ["-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3))]


def plot_probes(h, title, plots, units):
    names = probe_names(h)
    if not names:
        return
    rows = [("displacement", ["ux", "uy", "uz"]), ("velocity", ["vx", "vy", "vz"]),
            ("Cauchy stress", ["sxx", "syy", "szz", "sxy", "sxz", "syz"])]
    colours = plt.get_cmap("tab10" if len(names) <= 10 else "tab20").colors
    fig, axes = plt.subplots(len(rows), 1, figsize=(10, 9), sharex=True)
    for ax, (label, components) in zip(axes, rows):
        for p, name in enumerate(names):
            present = [c for c in components if f"probe_{name}_{c}" in h]
            for k, component in enumerate(present):
                ax.plot(h["time"], h[f"probe_{name}_{component}"], color=colours[p % len(colours)],
                        linestyle=LINE_STYLES[k % len(LINE_STYLES)], label=f"{name}: {component}")
        ax.set_ylabel(axis_label(label, units))
        ax.grid(alpha=0.3)
        # Beside the axes, not over the data.
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small",
                  ncol=1 + len(names) * len(components) // 13)
    axes[0].set_title(short_title(title) or "probes")
    axes[-1].set_xlabel(axis_label("time", units))
    fig.tight_layout()
    save(fig, plots, "probes.png")


def last_vtu(directory):
    pvd = os.path.join(directory, "results.pvd")
    if not os.path.exists(pvd):
        return None
    # Only the particles (part 0, or no part): an implicit run adds its mesh as part 1 at every time.
    datasets = [d for d in ET.parse(pvd).getroot().iter("DataSet") if d.get("part", "0") == "0"]
    if not datasets:
        return None
    return os.path.join(directory, datasets[-1].get("file")), datasets[-1].get("timestep")


def plot_final_state(directory, title, plots, units):
    """The last .vtu file's particles coloured by speed: the plane in 2-D; in 3-D the projections
    on the x-y and x-z planes (each particle drawn where it projects, nearer ones on top)."""
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
    speed = np.linalg.norm(v, axis=1) if v is not None else None
    plastic = mesh.point_data.get("plastic_strain")
    plastic = np.ravel(plastic) if plastic is not None and np.max(plastic) > 0 else None  # plastic materials
    three_d = np.any(x[:, 2] != 0)
    planes = [(0, 1, 2), (0, 2, 1)] if three_d else [(0, 1, None)]
    # Constrained layout keeps the title, the axis labels and the colour bars inside the figure.
    fig, axes = plt.subplots(1, len(planes), figsize=(7 * len(planes), 6.5), squeeze=False, layout="constrained")
    names = "xyz"
    for ax, (a, b, depth) in zip(axes[0], planes):
        order = np.argsort(x[:, depth]) if depth is not None else np.arange(len(x))
        if depth == 1:
            order = order[::-1]  # looking along +y: smaller y is nearer
        field = plastic if plastic is not None else speed
        colour = field[order] if field is not None else None
        dots = ax.scatter(x[order, a], x[order, b], c=colour, s=4, cmap="magma_r" if plastic is not None else "viridis")
        ax.set_aspect("equal")
        ax.set_xlabel(axis_label(names[a], units) if not units.get("length") else f"{names[a]} [{units['length']}]")
        ax.set_ylabel(axis_label(names[b], units) if not units.get("length") else f"{names[b]} [{units['length']}]")
        if three_d:
            ax.set_title(f"projection on the {names[a]}-{names[b]} plane", fontsize="medium")
        if plastic is not None:
            fig.colorbar(dots, ax=ax, label="equivalent plastic strain")
        elif speed is not None:
            fig.colorbar(dots, ax=ax, label=axis_label("velocity", units).replace("velocity", "speed"))
    when = f"t = {float(time):.6g} ({os.path.basename(vtu)})"
    fig.suptitle(f"{short_title(title)}\n{when}" if title else when)
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
    units = summary.get("input", {}).get("units", {}) if isinstance(summary.get("input"), dict) else {}
    h = read_history(history_file)
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    plot_energy(h, title, plots, units)
    plot_momentum(h, title, plots, units)
    plot_probes(h, title, plots, units)
    plot_newton(h, title, plots, units)
    plot_temperature(h, title, plots, units)
    if "momentum_y" in h:  # 2-D and 3-D
        plot_final_state(directory, title, plots, units)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except Exception as error:  # a clear one-line message instead of a traceback
        print(f"plot_history.py: {type(error).__name__}: {error}", file=sys.stderr)
        sys.exit(1)
