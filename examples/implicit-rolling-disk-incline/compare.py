#!/usr/bin/env python3
"""Iaconeta 2017 §5.2 (Table 1) side by side: the disk on the 60 degree incline solved by the
implicit UL MPM (solver.basis "mesh") and the Galerkin meshfree method with MLS and LME functions
(solver.basis "mls", "lme"; §4.2) on one input, at dt1, dt2, dt3. Prints the fitted acceleration over
the rolling one (rolling_acceleration_ratio: 1 rolling, 1.5 sliding), the relative displacement error
at t_end against rolling (rolling_final_displacement_error), eq. (67) (rolling_displacement_error_norm,
m), the wall time, and each meshfree run's wall time over the MPM run's beside Table 1's ratio.

    examples/implicit-rolling-disk-incline/compare.py BUILD/matpoint [INPUT] [--dt 1e-3,5e-4] [--gamma G]
        [--mls-radius F --mls-dilation F] [--methods mesh,mls,lme]

INPUT: default input.json, the frictionless control (the meshfree body's floor nodes slide with it);
no-slip.json rolls the disk on the one-sided no-slip floor, which acts on the points' surface feet
for MPM and the meshfree method alike (docs/input.md). The paper's MLS clouds for this test: --mls-radius 4.2426 --mls-dilation 2.8284
(R = 1.5 "2h sqrt 2", R_eff = "2h sqrt 2", extraction §6.4). --methods runs a subset (the run-time
ratio needs "mesh" in it), e.g. --methods lme --gamma 0.8 for Table 1's gamma study. README.md has
the last output.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MEASURES = ["rolling_acceleration_ratio", "rolling_final_displacement_error", "rolling_displacement_error_norm"]
# Table 1 (extraction §8.2): t_comp of GMM / t_comp of MPM at dt1, dt2, dt3
TABLE1_RATIO = {"mls": (1.138, 1.093, 1.097), "lme": (1.019, 0.974, 1.123)}


def load(path):
    text = open(path).read()
    return json.loads("\n".join(line for line in text.splitlines() if not line.lstrip().startswith("//")))


def case(base, basis, dt, options):
    spec = json.loads(json.dumps(base))
    spec["solver"]["basis"] = basis
    spec["solver"]["dt"] = dt
    if basis == "lme" and options.get("gamma"):
        spec["solver"]["meshfree"] = {"gamma": options["gamma"]}
    if basis == "mls" and options.get("mls_radius"):
        spec["solver"]["meshfree"] = {"radius_factor": options["mls_radius"]}
        if options.get("mls_dilation"):
            spec["solver"]["meshfree"]["dilation_factor"] = options["mls_dilation"]
    spec["checks"] = [{"name": m, "measure": m, "expected": 0, "tolerance": 0, "kind": "regression",
                       "source": "reported by compare.py"} for m in MEASURES]
    spec["output"]["particles"] = False
    spec["output"]["plots"] = False
    return spec


def run(binary, spec):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "input.json")
        json.dump(spec, open(path, "w"))
        out = os.path.join(tmp, "out")
        done = subprocess.run([binary, "run", path, "--out", out, "--threads", "1"], check=False,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            return None, done.stderr.strip().splitlines()[-1] if done.stderr.strip() else str(done.returncode)
        summary = json.load(open(os.path.join(out, "summary.json")))
    return {c["measure"]: c["measured"] for c in summary["checks"]}, summary


def option(argv, name):
    return argv[argv.index(name) + 1] if name in argv else None


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    binary = argv[1]
    given = [a for a in argv[2:] if a.endswith(".json")]
    base = load(given[0] if given else os.path.join(HERE, "input.json"))
    dts = [float(x) for x in (option(argv, "--dt") or "1e-3,5e-4,2.5e-4").split(",")]
    options = {"gamma": option(argv, "--gamma"), "mls_radius": option(argv, "--mls-radius"),
               "mls_dilation": option(argv, "--mls-dilation")}
    options = {k: float(v) for k, v in options.items() if v}
    methods = (option(argv, "--methods") or "mesh,mls,lme").split(",")
    print(f"{'method':8} {'dt (s)':>8} {'a / (2/3 g sin)':>15} {'u(t_end) err':>12} {'eq. (67) m':>10} "
          f"{'wall s':>7} {'/ MPM':>6} {'Table 1':>7}")
    for k, dt in enumerate(dts):
        mpm_wall = None
        for basis, name in (("mesh", "MPM"), ("mls", "GMM-MLS"), ("lme", "GMM-LME")):
            if basis not in methods:
                continue
            measured, summary = run(binary, case(base, basis, dt, options))
            if measured is None:
                print(f"{name:8} {dt:8.2e} failed: {summary}", flush=True)
                continue
            wall = summary["wall_time_seconds"]
            mpm_wall = wall if basis == "mesh" else mpm_wall
            ratio = f"{wall / mpm_wall:6.2f}" if basis != "mesh" and mpm_wall else f"{'':6}"
            paper = f"{TABLE1_RATIO[basis][min(k, 2)]:7.3f}" if basis != "mesh" else f"{'':7}"
            print(f"{name:8} {dt:8.2e} {measured[MEASURES[0]]:15.4f} {measured[MEASURES[1]]:12.4f} "
                  f"{measured[MEASURES[2]]:10.4f} {wall:7.1f} {ratio} {paper}", flush=True)


if __name__ == "__main__":
    main(sys.argv)
