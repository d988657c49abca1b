#!/usr/bin/env python3
"""Regenerates the benchmark table of docs/verification.md: scripts/verification_table.py [--build DIR]

Runs every example input that carries reference checks (examples/*/input*.json with "checks") and the
built-in verification problems (`matpoint verify --json`), then rewrites the part of
docs/verification.md between the markers

    <!-- BEGIN GENERATED: benchmark table (scripts/verification_table.py) -->
    <!-- END GENERATED -->

with one row per check: benchmark, check, expected, tolerance, measured, status, source. Runs go to
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
    result = subprocess.run([matpoint, "run", path, "--out", out, "--quiet"], capture_output=True, text=True)
    summary_file = os.path.join(out, "summary.json")
    if result.returncode != 0 or not os.path.exists(summary_file):
        return [(label, "run", "exit 0", "", f"exit {result.returncode}", "FAIL", result.stderr.strip()[-200:])]
    if figures and file == "input.json":
        save_figures(name, out)
    rows = []
    for c in json.load(open(summary_file)).get("checks", []):
        rows.append((f"examples/{label}", c["name"], fmt(c["expected"]), fmt(c["tolerance"]), fmt(c["measured"]),
                     "pass" if c["pass"] else "FAIL", c.get("source", "")))
    return rows


def run_verify(matpoint):
    out = os.path.join(ROOT, "out", "verification", "verify")
    result = subprocess.run([matpoint, "verify", "--json", "--out", out], capture_output=True, text=True)
    try:
        checks = json.loads(result.stdout)
    except ValueError:
        return [("matpoint verify", "run", "exit 0", "", f"exit {result.returncode}", "FAIL", result.stderr[-200:])]
    rows = []
    for c in checks:
        expected = f"{c.get('relation', '')} {fmt(c['expected'])}".strip()
        rows.append((f"verify {c['name']}", c.get("method", ""), expected, fmt(c.get("tolerance", "")),
                     fmt(c["measured"]), "pass" if c["pass"] else "FAIL", c.get("source", "")))
    return rows


def table(rows):
    lines = ["| benchmark | check | expected | tolerance | measured | status | source |",
             "|---|---|---|---|---|---|---|"]
    for row in rows:
        lines.append("| " + " | ".join(str(cell).replace("|", "/").replace("\n", " ") for cell in row) + " |")
    return "\n".join(lines)


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

    doc_path = os.path.join(ROOT, "docs", "verification.md")
    doc = open(doc_path).read()
    passed = sum(r[5] == "pass" for r in rows)
    block = (f"{BEGIN}\n{passed} of {len(rows)} checks pass. Regenerate with `scripts/verification_table.py` "
             f"(runs every example with checks and `matpoint verify`).\n\n{table(rows)}\n{END}")
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
