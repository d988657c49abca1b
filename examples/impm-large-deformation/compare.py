#!/usr/bin/env python3
"""Runs the two-disk collision with MPM, IMPM and improved CPDI, prints energy error, smallest
det F and cost per particle-step of each, and draws compare.png (energy and hourglass energy
against time). Usage: python3 compare.py [path/to/matpoint] [--threads N]"""
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "scripts"))
from example_tools import load_input, run_spec  # noqa: E402

matpoint = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else "build/matpoint"
threads = sys.argv[sys.argv.index("--threads") + 1] if "--threads" in sys.argv else "1"
out_root = os.path.join("out", "impm-large-deformation")
cases = [("MPM", "input-mpm.json"), ("IMPM", "input-impm.json"), ("improved CPDI", "input.json")]

results = {}
for label, name in cases:
    out = os.path.join(out_root, name.replace(".json", ""))
    result = run_spec(matpoint, load_input(here, name), threads, out=out)
    results[label] = (result.summary, result.history)

print("| method | status | max energy error | final energy / initial | min det F | max hourglass energy / E0 "
      "| MLS fallbacks | particle-steps / s (wall) | microseconds per particle-step |")
print("|---|---|---|---|---|---|---|---|---|")
for label, (s, rows) in results.items():
    e0 = float(rows[0]["total_energy"])
    err = max(abs(float(r["total_energy"]) - e0) / e0 for r in rows)
    hg = max(float(r["hourglass_energy"]) for r in rows) / e0
    rate = s["particle_steps_per_second"]
    print(f"| {label} | {s['status']} | {100 * err:.1f} % | {float(rows[-1]['total_energy']) / e0:.3f} | "
          f"{min(float(r['min_jacobian']) for r in rows):.3f} | {hg:.2e} | {s.get('mls_fallbacks', '-')} | "
          f"{rate:.3g} | {1e6 / rate:.2f} |")

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("no matplotlib: table only (install python3-matplotlib for compare.png)")
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
for label, (s, rows) in results.items():
    t = [float(r["time"]) for r in rows]
    e0 = float(rows[0]["total_energy"])
    a.plot(t, [float(r["total_energy"]) / e0 for r in rows], label=label)
    b.semilogy(t, [max(float(r["hourglass_energy"]) / e0, 1e-16) for r in rows], label=label)
a.set_xlabel("time (s)"); a.set_ylabel("total energy / initial"); a.set_title("energy"); a.legend()
b.set_xlabel("time (s)"); b.set_ylabel("hourglass energy / initial total"); b.set_title("hourglass energy")
fig.tight_layout()
fig.savefig(os.path.join(out_root, "compare.png"), dpi=120)
print("wrote", os.path.join(out_root, "compare.png"))
