#!/usr/bin/env python3
"""Aulisa & Capodaglio eq. (52) from a run's history.csv: the averaged relative error of the centre
particle's displacement along the plane against the rigid rolling disk, x(t) = g sin(theta) t^2 / 3
(eq. (49)), over the output times t_i > 0.

    examples/implicit-rolling-disk/error.py OUT_DIR [theta_degrees=45]
"""
import csv
import math
import sys


def rolling_error(out_dir, theta=45.0):
    """(eq. (52), the centre particle's displacement at the last output)."""
    g = 9.81
    rows = list(csv.DictReader(open(f"{out_dir}/history.csv")))
    x0 = float(rows[0]["probe_centre_x"])
    errors = []
    for row in rows[1:]:
        t = float(row["time"])
        exact = g * math.sin(math.radians(theta)) * t * t / 3.0
        errors.append(abs(exact - (float(row["probe_centre_x"]) - x0)) / exact)
    return sum(errors) / len(errors), float(rows[-1]["probe_centre_x"]) - x0


def main(out_dir, theta=45.0):
    error, x = rolling_error(out_dir, theta)
    rows = list(csv.DictReader(open(f"{out_dir}/history.csv")))
    t = float(rows[-1]["time"])
    rigid = 9.81 * math.sin(math.radians(theta)) * t * t / 3.0
    print(f"steps {len(rows) - 1}, x({t:g} s) = {x:.4f} m (rigid rolling {rigid:.4f} m), error (52) = {error:.4e}")

if __name__ == "__main__":
    main(sys.argv[1], *(float(a) for a in sys.argv[2:3]))
