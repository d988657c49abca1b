#!/usr/bin/env python3
"""Test B's refinement study (Aulisa & Capodaglio Fig. 8): runs input.json at J = JMIN..JMAX and
prints the tip's free-vibration period, amplitude decay and centre offset (the measures of the
input's checks, from summary.json), the energy K + U lost after the release and the equilibrium
defect's work over the same time (history.csv; README.md, "Why the free vibration is damped on
fine meshes"), with each run's cost.

    examples/implicit-cantilever/sweep.py BUILD/matpoint [JMAX=3] [THREADS=2] [JMIN=2]
                                          [--particles input|authors] [--end T] [--element E]

--particles input (default): the input's 23 040 particles at every J, as the paper states for the
test. --particles authors: the particle set the authors' code (MyFEMuS
applications/MPM_FEM/ex2/ex2.cpp, the comments beside H0, rows and factor) pairs with each mesh:
(H0, N_H, f) = (0.15, 20, 1.148) at J = 2, (0.2, 40, 1.2) at J = 3, (0.225, 80, 1.224) at J = 4,
that is 23 040, 70 008 and 178 790 particles. --end T stops at t = T (default: the input's 8 s);
T = 2.4 gives two and a half cycles after the release, enough for the decay rate. --element
bspline2 runs the same levels on the C1 B-spline background (J refinements of the 2 x 2 cells: the
Q9 mesh's element size, a quarter of its nodes at J = 4) instead of the input's Q9 elements.

The paper shows J = 2, 3, 4 and says only that the oscillations drift slightly out of phase as the
mesh is refined; the periods should agree within about 5 %. README.md has the last output. J = 4
takes long (with --particles authors about 25 min per 300 steps on one loaded thread).
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MEASURES = ("free_vibration_period", "free_vibration_amplitude_decay", "free_vibration_mean_offset")
# MyFEMuS ex2.cpp: "H0 = 0.15; //0.15: 3ref, 0.2: 4 ref, 0.225: 5 ref", "rows = 20; // 20: 3 ref,
# 40: 4 ref, 80: 5 ref", "factor = 1.148; //1.148: 3 ref, 1.224: 5 ref, 1.2: 4 ref"; its "n ref" mesh
# levels are J = n - 1 refinements of the 2 x 2 coarse mesh.
AUTHORS_PARTICLES = {2: (0.15, 20, 1.148), 3: (0.2, 40, 1.2), 4: (0.225, 80, 1.224)}
RELEASE = 0.4  # gravity is off from step 50 (t = 0.4 s) on


def strip_comments(text):
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//"))


def measured(summary):
    values = {check["measure"]: check["measured"] for check in summary["checks"]}
    return [float("nan") if values[m] is None else values[m] for m in MEASURES]  # None: too few cycles


def energy_after_release(history_path):
    """(K + U lost after the release as a fraction of K + U at the release, defect work / that)."""
    rows = list(csv.DictReader(open(history_path)))
    start = next(r for r in rows if float(r["time"]) >= RELEASE - 1e-9)
    end = rows[-1]

    def energy(r):
        return float(r["kinetic_energy"]) + float(r["strain_energy"])

    e0 = energy(start)
    defect = float(end["equilibrium_defect_work"]) - float(start["equilibrium_defect_work"])
    return (e0 - energy(end)) / e0, -defect / e0


def main(binary, jmax=3, threads=2, jmin=2, particles="input", end=None, element=None):
    print(f"{'J':>2} {'particles':>9} {'elements':>8} {'period s':>9} {'decay':>8} {'offset':>8} {'E lost':>7} "
          f"{'defect':>7} {'cuts':>4} {'wall s':>7} {'Newton':>6} {'assembly s':>10} {'factor+solve s':>14}")
    spec = json.loads(strip_comments(open(os.path.join(HERE, "input.json")).read()))
    for j in range(jmin, jmax + 1):
        spec["mesh"]["refine"] = j
        if element is not None:
            spec["mesh"]["element"] = element
        spec["output"]["plots"] = False
        if end is not None:
            spec["solver"]["end_time"] = end
        if particles == "authors":
            shape = spec["bodies"][0]["shape"]
            shape["core_height"], shape["core_rows"], shape["layer_growth"] = AUTHORS_PARTICLES[j]
        with tempfile.TemporaryDirectory() as work:
            path = os.path.join(work, "input.json")
            json.dump(spec, open(path, "w"))
            subprocess.run([binary, "run", path, "--out", os.path.join(work, "out"), "--threads", str(threads)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            summary = json.load(open(os.path.join(work, "out", "summary.json")))
            lost, defect = energy_after_release(os.path.join(work, "out", "history.csv"))
        imp = summary["implicit"]
        period, decay, offset = measured(summary)
        print(f"{j:>2} {summary['particles']:>9} {imp['mesh_elements']:>8} {period:>9.4f} {decay:>8.4f} "
              f"{offset:>8.4f} {lost:>7.4f} {defect:>7.4f} {imp['step_cuts']:>4} {summary['wall_time_seconds']:>7.1f} "
              f"{imp['newton_iterations']:>6} {imp['assembly_seconds']:>10.1f} "
              f"{imp['factorization_seconds'] + imp['solve_seconds']:>14.1f}", flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    options = {}
    for flag in ("--particles", "--end", "--element"):
        if flag in args:
            k = args.index(flag)
            options[flag[2:]] = args[k + 1]
            del args[k:k + 2]
    if "end" in options:
        options["end"] = float(options["end"])
    main(args[0], *(int(a) for a in args[1:4]), **options)
