#!/usr/bin/env python3
"""Test A's refinement study (Aulisa & Capodaglio Table 1): runs input.json (E1 = 4.2 MPa) and
input-stiff.json (E2 = 420 MPa) at J = 1..JMAX with the gap d0 - R = 0.2 / 2^(J-1) (E1) or
0.3 / 2^(J-1) (E2) of the paper's §6.2 (Table 1's set-up), and prints eq. (52) and x(2.5 s) beside the paper's values.

    examples/implicit-rolling-disk/sweep.py BUILD/matpoint [JMAX=2] [THREADS=2] [JMIN=1]

Beside the errors it prints each run's cost from summary.json: wall time, Newton iterations, and
the assembly (residual + AD Jacobian) and factorisation + solve seconds.

J = 3 and 4 take long (J = 4: 82 689 nodes); README.md has the last output.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from error import rolling_error  # noqa: E402

PAPER = {"input.json": [5.545e-2, 3.921e-2, 2.571e-2, 2.253e-2],
         "input-stiff.json": [4.520e-2, 3.502e-2, 2.423e-2, 1.720e-2]}
GAP = {"input.json": 0.2, "input-stiff.json": 0.3}


def strip_comments(text):
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//"))


def main(binary, jmax=2, threads=2, jmin=1):
    print(f"{'input':18} {'J':>2} {'paper (52)':>11} {'ours (52)':>10} {'x(2.5) m':>9} {'nodes':>6} "
          f"{'wall s':>7} {'Newton':>6} {'assembly s':>10} {'factor+solve s':>14}")
    for name in ("input.json", "input-stiff.json"):
        spec = json.loads(strip_comments(open(os.path.join(HERE, name)).read()))
        for j in range(jmin, jmax + 1):
            y = -1.6 + 1.6 + GAP[name] / 2 ** (j - 1)
            spec["mesh"]["refine"] = j
            spec["bodies"][0]["shape"]["center"] = [0, y]
            spec["output"]["probes"][0]["position"] = [0, y]
            spec["output"]["plots"] = False
            spec["checks"] = []
            with tempfile.TemporaryDirectory() as work:
                path = os.path.join(work, "input.json")
                json.dump(spec, open(path, "w"))
                subprocess.run([binary, "run", path, "--out", os.path.join(work, "out"), "--threads", str(threads)],
                               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                error, x = rolling_error(os.path.join(work, "out"))
                summary = json.load(open(os.path.join(work, "out", "summary.json")))
            imp = summary["implicit"]
            print(f"{name:18} {j:>2} {PAPER[name][j - 1]:>11.3e} {error:>10.3e} {x:>9.3f} {imp['mesh_nodes']:>6} "
                  f"{summary['wall_time_seconds']:>7.1f} {imp['newton_iterations']:>6} {imp['assembly_seconds']:>10.1f} "
                  f"{imp['factorization_seconds'] + imp['solve_seconds']:>14.1f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], *(int(a) for a in sys.argv[2:5]))
