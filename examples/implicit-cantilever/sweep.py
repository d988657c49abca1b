#!/usr/bin/env python3
"""Test B's refinement study (Aulisa & Capodaglio Fig. 8): runs input.json at J = JMIN..JMAX and
prints the tip's free-vibration period, amplitude decay and centre offset (the measures of the
input's checks, from summary.json) with each run's cost.

    examples/implicit-cantilever/sweep.py BUILD/matpoint [JMAX=3] [THREADS=2] [JMIN=2]

The paper shows J = 2, 3, 4 and says only that the oscillations drift slightly out of phase as the
mesh is refined; the periods should agree within about 5 %. README.md has the last
output. J = 4 (32 x 32 Q9) takes long.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MEASURES = ("free_vibration_period", "free_vibration_amplitude_decay", "free_vibration_mean_offset")


def strip_comments(text):
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//"))


def measured(summary):
    values = {check["measure"]: check["measured"] for check in summary["checks"]}
    return [values[m] for m in MEASURES]


def main(binary, jmax=3, threads=2, jmin=2):
    print(f"{'J':>2} {'elements':>8} {'period s':>9} {'decay':>8} {'offset':>8} {'cuts':>4} {'wall s':>7} "
          f"{'Newton':>6} {'assembly s':>10} {'factor+solve s':>14}")
    spec = json.loads(strip_comments(open(os.path.join(HERE, "input.json")).read()))
    for j in range(jmin, jmax + 1):
        spec["mesh"]["refine"] = j
        spec["output"]["plots"] = False
        with tempfile.TemporaryDirectory() as work:
            path = os.path.join(work, "input.json")
            json.dump(spec, open(path, "w"))
            subprocess.run([binary, "run", path, "--out", os.path.join(work, "out"), "--threads", str(threads)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            summary = json.load(open(os.path.join(work, "out", "summary.json")))
        imp = summary["implicit"]
        period, decay, offset = measured(summary)
        print(f"{j:>2} {imp['mesh_elements']:>8} {period:>9.4f} {decay:>8.4f} {offset:>8.4f} {imp['step_cuts']:>4} "
              f"{summary['wall_time_seconds']:>7.1f} {imp['newton_iterations']:>6} {imp['assembly_seconds']:>10.1f} "
              f"{imp['factorization_seconds'] + imp['solve_seconds']:>14.1f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], *(int(a) for a in sys.argv[2:5]))
