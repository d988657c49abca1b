#!/usr/bin/env python3
"""Regenerates the benchmark table of docs/verification.md: scripts/verification_table.py [--build DIR]

Runs every example input that carries reference checks (examples/*/input*.json with "checks") and the
built-in verification problems (`matpoint verify --json`), then rewrites the part of
docs/verification.md between the markers

    <!-- BEGIN GENERATED: benchmark table (scripts/verification_table.py) -->
    <!-- END GENERATED -->

with one row per check: benchmark, check, kind, expected, tolerance, measured, status, source, and
the count of each kind:
  verification  the reference is independent of the code (analytic, a paper's value, a converged
                finer run named in the source); the built-in `matpoint verify` checks, the Courant
                bounds of `matpoint dispersion` (Gong 2015 (7.29) with the square) and the measured
                Courant limits of the real 1-D loop (`matpoint stability-scan`, against an independent
                numpy reproduction of that loop, docs/theory/stability.md);
  regression    a value from an earlier run of this code, kept beside an independent check;
  guard         a sanity bound that catches only gross failure (an inverted particle).
An example check's kind is its input's `kind` (default "verification"). Runs go to
out/verification/. Exit 0 when every check passes, 1 otherwise (the table is written either way).

--figures also redraws each example's plots at low resolution into examples/NAME/figures/
(energy.png, and final_state.png for 2-D runs) and shows them in examples/NAME/README.md between
generated markers.
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN = "<!-- BEGIN GENERATED: benchmark table (scripts/verification_table.py) -->"
END = "<!-- END GENERATED -->"


def strip_comments(text):
    """The input format allows // comments on their own lines; enough to find the checks key."""
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//"))


KINDS = ("verification", "regression", "guard")


def input_check_kinds(path):
    """{check name: kind} of an input file (the summary does not carry the kind)."""
    try:
        spec = json.loads(strip_comments(open(path).read()))
    except ValueError:
        return {}
    return {c.get("name"): c.get("kind", "verification") for c in spec.get("checks", [])}


def examples_with_checks():
    """(example, input file) of every examples/NAME/input*.json that carries checks."""
    folder = os.path.join(ROOT, "examples")
    for name in sorted(os.listdir(folder)):
        inputs = sorted(f for f in os.listdir(os.path.join(folder, name))
                        if f.startswith("input") and f.endswith(".json"))
        for file in sorted(inputs, key=lambda f: f != "input.json"):  # the main input first
            path = os.path.join(folder, name, file)
            try:
                spec = json.loads(strip_comments(open(path).read()))
            except ValueError:
                spec = {"checks": [True]}  # block comments: let matpoint read it
            if spec.get("checks"):
                yield name, file, path


def fmt(x):
    if isinstance(x, bool):
        return str(x).lower()
    if isinstance(x, (int, float)):
        return f"{x:.4g}"
    return str(x)


def save_figures(name, out):
    """Low-resolution copies of the run's plots for the example's README (examples/NAME/figures/)."""
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    env = dict(os.environ, MATPOINT_PLOT_DPI="50")
    subprocess.run([python, os.path.join(ROOT, "scripts", "plot_history.py"), out], env=env, check=False)
    folder = os.path.join(ROOT, "examples", name, "figures")
    os.makedirs(folder, exist_ok=True)
    shown = []
    for plot in ("energy.png", "final_state.png"):
        source = os.path.join(out, "plots", plot)
        if os.path.exists(source):
            with open(source, "rb") as f, open(os.path.join(folder, plot), "wb") as g:
                g.write(f.read())
            shown.append(plot)
    show_in_readme(os.path.join(ROOT, "examples", name, "README.md"), shown)


FIGURES_BEGIN = "<!-- BEGIN GENERATED: figures (scripts/verification_table.py --figures) -->"


def show_in_readme(readme, plots):
    """Puts the plots into the example's README between generated markers (after the title
    section, or replacing the previous block)."""
    if not plots or not os.path.exists(readme):
        return
    captions = {"energy.png": "energies and momentum against time (`plots/energy.png` of the run)",
                "final_state.png": "the particles at the end, coloured by a field (`plots/final_state.png`)"}
    block = FIGURES_BEGIN + "\n" + "\n".join(
        f"![{captions[p]}](figures/{p})" for p in plots) + "\n" + END
    text = open(readme).read()
    if FIGURES_BEGIN in text:
        start = text.index(FIGURES_BEGIN)
        text = text[:start] + block + text[text.index(END, start) + len(END):]
    else:
        text = text.rstrip() + "\n\n## Plots (the shipped input)\n" + block + "\n"
    with open(readme + ".partial", "w") as f:
        f.write(text)
    os.replace(readme + ".partial", readme)


def run_example(matpoint, name, file, path, figures=False):
    label = name if file == "input.json" else f"{name}/{file}"
    out = os.path.join(ROOT, "out", "verification", label.replace("/", "-").removesuffix(".json"))
    result = subprocess.run([matpoint, "run", path, "--out", out, "--quiet", "--overwrite"], capture_output=True, text=True)
    summary_file = os.path.join(out, "summary.json")
    if result.returncode != 0 or not os.path.exists(summary_file):
        return [(label, "run", "verification", "exit 0", "", f"exit {result.returncode}", "FAIL",
                 result.stderr.strip()[-200:])]
    if figures and file == "input.json":
        save_figures(name, out)
    kinds = input_check_kinds(path)
    rows = []
    for c in json.load(open(summary_file)).get("checks", []):
        rows.append((f"examples/{label}", c["name"], kinds.get(c["name"], "verification"), fmt(c["expected"]),
                     fmt(c["tolerance"]), fmt(c["measured"]), "pass" if c["pass"] else "FAIL", c.get("source", "")))
    return rows


def run_verify(matpoint):
    out = os.path.join(ROOT, "out", "verification", "verify")
    result = subprocess.run([matpoint, "verify", "--json", "--out", out], capture_output=True, text=True)
    try:
        checks = json.loads(result.stdout)
    except ValueError:
        return [("matpoint verify", "run", "verification", "exit 0", "", f"exit {result.returncode}", "FAIL",
                 result.stderr[-200:])]
    rows = []
    for c in checks:
        expected = f"{c.get('relation', '')} {fmt(c['expected'])}".strip()
        rows.append((f"verify {c['name']}", c.get("method", ""), c.get("kind", "verification"), expected,
                     fmt(c.get("tolerance", "")), fmt(c["measured"]), "pass" if c["pass"] else "FAIL",
                     c.get("source", "")))
    return rows


# Gong 2015 (7.29) with the square restored: the tight Courant bounds of the linear analysis for
# N_p^e = 1..4, to 1e-4 (docs/theory/stability.md, "Tight bound of (7.29)").
DISPERSION_BOUNDS = {1: 1.0, 2: 1.29904, 3: 1.34479, 4: 1.36035}


def run_dispersion(matpoint):
    out = os.path.join(ROOT, "out", "verification", "dispersion")
    result = subprocess.run([matpoint, "dispersion", "--json", "--no-plots", "--out", out,
                             "--particles-per-cell", *map(str, DISPERSION_BOUNDS)], capture_output=True, text=True)
    try:
        bounds = {int(b["particles_per_cell"]): b for b in json.loads(result.stdout)["bounds"]}
    except (ValueError, KeyError, TypeError):
        return [("matpoint dispersion", "run", "verification", "exit 0", "", f"exit {result.returncode}", "FAIL",
                 result.stderr[-200:])]
    rows = []
    for n, expected in DISPERSION_BOUNDS.items():
        measured = bounds.get(n, {}).get("tight", float("nan"))
        rows.append((f"dispersion, {n} particle(s) per cell", "tight Courant bound of the linear analysis",
                     "verification", fmt(expected), "0.0001", fmt(measured),
                     "pass" if abs(measured - expected) <= 1e-4 else "FAIL",
                     "Gong 2015 eq. (7.29) with the square kept (the text drops it before (7.31); docs/theory/stability.md)"))
    return rows


# The real 1-D loop's Courant limit (examples/gong-stability-1d): an independent numpy reproduction of
# Gong's loop (docs/theory/stability.md) and, for one particle per cell, the FLIP 2h mode's 1/sqrt(2).
STABILITY_LIMITS = {1: (0.70711, "analytic: the FLIP 2h mode, sigma <- (1 - 4 CFL^2) sigma (docs/theory/stability.md)"),
                    2: (0.757, "independent numpy reproduction of Gong 2015's 1-D loop (docs/theory/stability.md, sigma = E(F - 1), 64 cells, 3000 steps)"),
                    4: (0.771, "independent numpy reproduction of Gong 2015's 1-D loop (docs/theory/stability.md, sigma = E(F - 1), 64 cells, 3000 steps)")}
SCAN_TOLERANCE = 0.003  # half-width of the bisection bracket


def run_stability(matpoint):
    rows = []
    path = os.path.join(ROOT, "examples", "gong-stability-1d", "input.json")
    for n, (expected, source) in STABILITY_LIMITS.items():
        result = subprocess.run([matpoint, "stability-scan", path, "--lo", "0.6", "--hi", "1.0", "--tolerance",
                                 str(SCAN_TOLERANCE), "--set", f"bodies.0.particles_per_cell={n}", "--json"],
                                capture_output=True, text=True)
        try:
            measured = float(json.loads(result.stdout)["limit"])
        except (ValueError, KeyError, TypeError):
            measured = float("nan")
        # the bracket's half-width plus the reproduction's last printed digit
        tolerance = SCAN_TOLERANCE + 0.002
        rows.append((f"stability-scan examples/gong-stability-1d, {n} particle(s) per cell",
                     "largest stable Courant number, FLIP, USL, linear basis", "verification", fmt(expected),
                     fmt(tolerance), fmt(measured), "pass" if abs(measured - expected) <= tolerance else "FAIL", source))
    return rows


def table(rows):
    lines = ["| benchmark | check | kind | expected | tolerance | measured | status | source |",
             "|---|---|---|---|---|---|---|---|"]
    for row in sorted(rows, key=lambda r: KINDS.index(r[2]) if r[2] in KINDS else len(KINDS)):
        lines.append("| " + " | ".join(str(cell).replace("|", "/").replace("\n", " ") for cell in row) + " |")
    return "\n".join(lines)


def counts(rows):
    """'40 of 40 verification checks pass; 4 of 4 regression values hold; 5 of 5 guards hold.'"""
    words = {"verification": "verification checks (independent references) pass",
             "regression": "regression values (earlier runs of this code, not references) hold",
             "guard": "guards (gross-failure bounds, not verification) hold"}
    parts = []
    for kind in KINDS:
        of_kind = [r for r in rows if r[2] == kind]
        parts.append(f"{sum(r[6] == 'pass' for r in of_kind)} of {len(of_kind)} {words[kind]}")
    return "; ".join(parts) + "."


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder holding matpoint")
    parser.add_argument("--figures", action="store_true", help="redraw examples/NAME/figures/*.png (small)")
    args = parser.parse_args()
    matpoint = os.path.join(args.build, "matpoint")
    if not os.path.exists(matpoint):
        sys.exit(f"verification_table.py: {matpoint} not found (run scripts/setup.sh)")
    rows = []
    for name, file, path in examples_with_checks():
        print(f"running examples/{name}/{file}", file=sys.stderr)
        rows += run_example(matpoint, name, file, path, args.figures)
    print("running matpoint verify", file=sys.stderr)
    rows += run_verify(matpoint)
    print("running matpoint dispersion and stability-scan", file=sys.stderr)
    rows += run_dispersion(matpoint)
    rows += run_stability(matpoint)

    doc_path = os.path.join(ROOT, "docs", "verification.md")
    doc = open(doc_path).read()
    passed = sum(r[6] == "pass" for r in rows)
    block = (f"{BEGIN}\n{counts(rows)} Regenerate with `scripts/verification_table.py` (runs every example with "
             f"checks, `matpoint verify`, `matpoint dispersion` and `matpoint stability-scan`).\n\n{table(rows)}\n{END}")
    if BEGIN in doc and END in doc:
        doc = doc[:doc.index(BEGIN)] + block + doc[doc.index(END) + len(END):]
    else:
        doc = doc.rstrip() + "\n\n## Every benchmark: expected, measured, status\n\n" + block + "\n"
    temporary = doc_path + ".partial"
    with open(temporary, "w") as f:
        f.write(doc)
    os.replace(temporary, doc_path)
    print(f"{passed} of {len(rows)} checks pass; table written to docs/verification.md", file=sys.stderr)
    return 0 if passed == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
