#!/usr/bin/python3
"""Error against run time: runs verification cases at a series of resolutions and scheme options,
records each run's error against the case's reference and its wall time, writes a CSV and one
work-precision diagram (error against wall time, log-log, a line per option set) per case, and
prints the observed order of convergence in the cell size.

  tools/accuracy.py                      # every study, figures to docs/figures/accuracy
  tools/accuracy.py --studies V1 V3 --out /tmp/acc --mpile build/release/bin/mpile

The built-in cases run through `mpile verify CASE --csv` (the quantity each study follows is
named below); V9 runs its case file through `mpile run` with the cell count changed and reads the
surface reactions from history.h5. Runs use one thread, so the times compare across options.
Uses Debian's python3-h5py, python3-numpy and python3-matplotlib (tools/setup.sh).
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Each study: the case, the quantity whose relative error is followed, the base cell size, the
# refinements, and the option sets (label -> extra `mpile verify` arguments).
STUDIES = {
    "V1": {
        "title": "V1 vibrating bar: centre-of-mass velocity amplitude",
        "quantity": "centre-of-mass velocity amplitude",
        "h": 1.0,
        "refinements": [1, 2, 4, 8],
        "options": {
            "MUSL, C = 0.8, 2x2 ppc": [],
            "MUSL, C = 0.4, 2x2 ppc": ["--courant", "0.4"],
            "MUSL, C = 0.8, FLIP 0.99": ["--flip", "0.99"],
            "MUSL, C = 0.8, XPIC(2)": ["--xpic", "2"],
            "MUSL, C = 0.8, XPIC(4)": ["--xpic", "4"],
            "USL, C = 0.8, 2x2 ppc": ["--scheme", "usl"],
            "MUSL, C = 0.8, 3x3 ppc": ["--ppc", "3"],
        },
    },
    "V3": {
        "title": "V3 Lame cylinder: max sigma_thth error",
        "quantity": "max sigma_thth error, 0.3 <= r <= 0.5",
        "h": 0.4 / 8,
        "refinements": [1, 2, 4],
        "options": {
            "B-bar, nu = 0.3": [],
            "no B-bar, nu = 0.3": ["--bbar", "0"],
            "B-bar, nu = 0.49": ["--poisson", "0.49"],
            "no B-bar, nu = 0.49": ["--bbar", "0", "--poisson", "0.49"],
            "B-bar, nu = 0.3, 3x3 ppc": ["--ppc", "3"],
        },
    },
    "V6": {
        "title": "V6 shaft torsion: cap torque",
        "quantity": "torque of the cap on the shaft",
        "h": 0.5 / 8,
        "refinements": [1, 2, 4],
        "options": {
            "MUSL, C = 0.8": [],
            "USL, C = 0.8": ["--scheme", "usl"],
            "MUSL, C = 0.4": ["--courant", "0.4"],
            "MUSL, C = 0.8, XPIC(2)": ["--xpic", "2"],
        },
    },
    "VHS": {
        "title": "VHS Hardening Soil oedometer: mean sigma_yy",
        "quantity": "mean sigma_yy",
        "h": 0.125,
        "refinements": [1, 2, 4],
        "options": {
            "MUSL, C = 0.8": [],
            "MUSL, C = 0.4": ["--courant", "0.4"],
            "USL, C = 0.8": ["--scheme", "usl"],
            "MUSL, C = 0.8, XPIC(2)": ["--xpic", "2"],
        },
    },
    "V9": {
        "title": "V9 torsion with adhesion: worst surface F_theta",
        "case_file": "cases/verification/v9_torsion_adhesion.toml",
        "h": 1.0,  # divided by the cell count below
        "cells": [10, 20, 40],
        "options": {
            "MUSL, C = 0.8": [],
            "MUSL, C = 0.4": ["courant_number = 0.4"],
            "MUSL, C = 0.8, XPIC(2)": ["xpic_order = 2"],
        },
    },
}

# V9 references: the theta forces on the pile once the whole interface slides (c_a r h, N/rad).
V9_REFERENCE = {"internal_shaft": -2000.0, "external_shaft": -3000.0, "base": -1000.0}


def run_verify(mpile, case, refinement, extra):
    command = [mpile, "verify", case, "--csv", "--threads", "1", "--refinement", str(refinement)] + extra
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.monotonic() - start
    # A run that stops (a guard caught an instability) prints its reason and no rows; a check out
    # of tolerance (exit 1 with rows) is still a measurement.
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    stopped = ""
    if not rows:
        lines = done.stderr.strip().splitlines()
        stopped = lines[-1] if lines else f"exit {done.returncode}"
    return rows, stopped, wall


def verify_point(mpile, study, refinement, extra):
    rows, stopped, wall = run_verify(mpile, study["case"], refinement, extra)
    if stopped:
        return float("nan"), wall, 0, 0, stopped
    for row in rows:
        if row["quantity"] == study["quantity"]:
            return (float(row["error"]), float(row["wall_seconds"]), int(row["particles"]), int(row["steps"]),
                    "")
    sys.exit(f"accuracy: {study['case']} reported no '{study['quantity']}'")


def v9_point(mpile, study, cells, extra):
    with open(os.path.join(ROOT, study["case_file"])) as f:
        text = f.read()
    text = text.replace("cells = 40", f"cells = {cells}")
    if extra:  # the V9 case file has no [solver] table: the options make one
        assert "[solver]" not in text
        text += "\n[solver]\n" + "\n".join(extra) + "\n"
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "v9.toml")
        with open(path, "w") as f:
            f.write(text)
        start = time.monotonic()
        done = subprocess.run([mpile, "run", path, "--threads", "1", "--out", directory + "/out"],
                              capture_output=True, text=True)
        wall = time.monotonic() - start
        if done.returncode != 0:
            return float("nan"), wall, 0, 0, done.stderr.strip().splitlines()[-1]
        with h5py.File(directory + "/out/history.h5", "r") as history:
            t = history["/time"][:]
            steps = int(history["/step"][-1])
            late = t >= 0.5
            error = 0.0
            for surface, reference in V9_REFERENCE.items():
                force = history[f"/reactions/pile/{surface}/F_theta"][:]
                mean = np.trapz(force[late], t[late]) / (t[late][-1] - t[late][0])
                error = max(error, abs(mean - reference) / abs(reference))
    # The V9 domain is filled with 2 x 2 particles per cell.
    return error, wall, 4 * cells * cells, steps, ""


def observed_order(h, error):
    """Least-squares slope of log(error) against log(h)."""
    if len(h) < 2 or min(error) <= 0.0:
        return float("nan")
    return float(np.polyfit(np.log(h), np.log(error), 1)[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--studies", nargs="*", default=list(STUDIES), help="which studies (default: all)")
    parser.add_argument("--mpile", default=os.path.join(ROOT, "build/release/bin/mpile"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs/figures/accuracy"), help="directory for CSV and PNGs")
    args = parser.parse_args()
    unknown = [s for s in args.studies if s not in STUDIES]
    if unknown:
        sys.exit(f"accuracy: unknown studies {unknown}; choose from {list(STUDIES)}")
    if not os.access(args.mpile, os.X_OK):
        sys.exit(f"accuracy: no mpile executable at {args.mpile} (build first, or pass --mpile)")
    os.makedirs(args.out, exist_ok=True)

    table = []
    for name in args.studies:
        study = dict(STUDIES[name], case=name)
        figure, axes = plt.subplots(figsize=(6.4, 4.6))
        print(f"{study['title']}")
        for label, extra in study["options"].items():
            hs, errors, walls = [], [], []
            levels = study.get("cells") or study["refinements"]
            for level in levels:
                h = study["h"] / level
                point = v9_point if "case_file" in study else verify_point
                error, wall, particles, steps, stopped = point(args.mpile, study, level, extra)
                table.append({"study": name, "options": label, "h": h, "particles": particles,
                              "steps": steps, "wall_seconds": wall, "error": error, "stopped": stopped})
                if stopped:
                    print(f"  {label:28s} h = {h:8.4f}  stopped: {stopped}")
                    continue
                hs.append(h)
                errors.append(error)
                walls.append(wall)
                print(f"  {label:28s} h = {h:8.4f}  {particles:7d} particles  {steps:6d} steps  "
                      f"{wall:8.2f} s  error {error:.3e}")
            order = observed_order(hs, errors)
            print(f"  {label:28s} observed order in h: {order:.2f}")
            for row in table:
                if row["study"] == name and row["options"] == label:
                    row["order"] = order
            axes.loglog(walls, [max(e, 1e-12) for e in errors], "o-", label=f"{label} (order {order:.1f})")
        axes.set_xlabel("wall time on one thread (s)")
        axes.set_ylabel("relative error")
        axes.set_title(study["title"], fontsize=10)
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=7)
        figure.tight_layout()
        png = os.path.join(args.out, f"{name.lower()}_work_precision.png")
        figure.savefig(png, dpi=110)
        plt.close(figure)
        print(f"  -> {png}")

    path = os.path.join(args.out, "accuracy.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["study", "options", "h", "particles", "steps", "wall_seconds",
                                               "error", "order", "stopped"])
        writer.writeheader()
        for row in table:
            writer.writerow(row)
    print(f"table -> {path}")


if __name__ == "__main__":
    main()
