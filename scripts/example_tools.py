"""Helpers shared by the examples' sweep scripts (examples/*/sweep.py, refine.py, scheme_table.py):
read an example's input.json, run matpoint on a modified copy, read back its summary and history.

    sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
    from example_tools import load_input, variant, run_spec
"""
import copy
import csv
import json
import os
import re
import subprocess
import tempfile
from dataclasses import dataclass, field


def load_input(folder, name="input.json"):
    """The example's input as a dict; the examples use whole-line // comments only."""
    with open(os.path.join(folder, name)) as f:
        text = f.read()
    return json.loads(re.sub(r"^\s*//.*$", "", text, flags=re.MULTILINE))


def variant(base, solver=None, drop_solver=("fmpm",), output=None):
    """A deep copy of `base`; `solver` keys replace those of base's solver after the keys in
    `drop_solver` are removed (so that switching transfer drops the FMPM options); `output`
    replaces the whole output object."""
    spec = copy.deepcopy(base)
    if solver is not None:
        for key in drop_solver:
            spec["solver"].pop(key, None)
        spec["solver"].update(solver)
    if output is not None:
        spec["output"] = output
    return spec


@dataclass
class RunResult:
    returncode: int
    summary: dict = field(default_factory=dict)
    history: list = field(default_factory=list)  # history.csv rows as dicts of strings
    stderr: str = ""
    out: str = ""  # the output folder when it is kept, else ""

    @property
    def ok(self):
        return self.returncode == 0

    def column(self, name):
        return [float(r[name]) for r in self.history]


def _read(out, proc, keep):
    summary_path, history_path = os.path.join(out, "summary.json"), os.path.join(out, "history.csv")
    summary = json.load(open(summary_path)) if os.path.exists(summary_path) else {}
    history = list(csv.DictReader(open(history_path))) if os.path.exists(history_path) else []
    return RunResult(proc.returncode, summary, history, proc.stderr, out if keep else "")


def run_spec(matpoint, spec, threads=1, out=None):
    """Runs `matpoint run` on `spec` in `out` (kept) or in a temporary folder (removed)."""
    def run_in(folder):
        path = os.path.join(folder, "input.json")
        with open(path, "w") as f:
            json.dump(spec, f, indent=1)
        proc = subprocess.run([matpoint, "run", path, "--out", folder, "--quiet", "--overwrite", "--threads", str(threads)],
                              capture_output=True, text=True)
        return _read(folder, proc, keep=out is not None)

    if out is not None:
        os.makedirs(out, exist_ok=True)
        return run_in(out)
    with tempfile.TemporaryDirectory() as folder:
        return run_in(folder)
