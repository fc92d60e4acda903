#!/usr/bin/python3
"""Stability on stiff and extreme cases: runs every case of cases/stability (some at several
settings), and for each run records whether it finished or which guard stopped it and why, the
number of steps, the time step at the start and at the end, the peak and final energy residual,
the wall time, and what the case measures against its reference. Writes a CSV and replaces the
table in docs/stability.md between its markers.

  tools/stability.py                                  # every row, docs/stability.md updated
  tools/stability.py --rows courant --threads 1 --no-docs

A setting is a text replacement in the case file (shown in the table), so every row is a case
file a user can run as it is. Uses Debian's python3-h5py, python3-numpy and python3-vtk9.
"""
import argparse
import csv
import glob
import math
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TABLE_START = "<!-- stability table: tools/stability.py writes between these markers -->"
TABLE_END = "<!-- end of stability table -->"


def last_particles(directory):
    """Positions, displacements and the point arrays of the last particle snapshot."""
    import vtk  # python3-vtk9; only the rows that measure particles need it
    from vtk.util.numpy_support import vtk_to_numpy

    files = sorted(glob.glob(os.path.join(directory, "particles_*.vtu")))
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(files[-1])
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    arrays = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
    return vtk_to_numpy(grid.GetPoints().GetData()), arrays


# What each case measures at its end, against its reference (a string for the table).
def measure_bar(history, directory):
    kinetic = history["energy/kinetic"][:]
    return f"kinetic energy at the end {kinetic[-1]:.4g} J/rad (0.03125 at the start, conserved)"


def measure_steel(history, directory):
    x, arrays = last_particles(directory)
    pile = arrays["body"] == 3  # the fourth body of the case
    return f"pile moved {-arrays['displacement'][pile, 1].mean():.3f} m down (its head 0.105 m)"


def measure_footing(history, directory):
    x, arrays = last_particles(directory)
    under = (x[:, 0] < 0.1) & (x[:, 1] > 1.9)
    settlement = -arrays["displacement"][under, 1].mean()
    return f"settlement at the centre {1000 * settlement:.2f} mm"


def measure_confinement(history, directory):
    dt = history["dt"][1:-1]
    return f"dt shrinks {dt[0] / dt[-1]:.2f} times as the stiffness grows"


def measure_disc(history, directory):
    force = history["reactions/disc/disc_surface/F_y"][-1]
    weight = 8000.0 * 9.81 * 0.1 * 0.4**2 / 2.0
    return f"contact F_y on the disc {force:.1f} N/rad (its weight {weight:.1f}, {100 * (force / weight - 1):+.2f} %)"


def measure_pile(history, directory):
    u = history["bodies/pile/u_y"][:]
    spin = np.abs(history["bodies/pile/angular_velocity"][:]).max()
    installation = history["phase"][:] == history["phase"][-1]
    duration = history["time"][-1] - history["time"][installation][0]
    return f"penetration {-u[-1]:.3f} m in {duration:.3f} s; peak spin {spin:.1f} rad/s"


def measure_collapse(history, directory):
    x, arrays = last_particles(directory)
    r_i, a = 0.5, 2.0
    runout = np.percentile(x[:, 0], 99.5)
    reference = r_i * (1.0 + 1.6 * math.sqrt(a))
    return (f"runout {runout:.2f} m (99.5 % of particles; front particle {x[:, 0].max():.2f}), "
            f"Lube et al. {reference:.2f} m ({100 * (runout / reference - 1):+.0f} %); "
            f"height {x[:, 1].max():.2f} m")


def measure_none(history, directory):
    return ""


def courant_rows():
    rows = []
    for c in ["0.1", "0.4", "0.8", "0.95", "1.0", "1.2"]:
        rows.append(("courant", "courant_bar.toml", f"C = {c}",
                     [("courant_number = 0.8", f"courant_number = {c}")], measure_bar))
    return rows


# (group, case file, setting, replacements, measurement)
ROWS = (courant_rows() + [
    ("steel", "steel_pile.toml", "as given (mass-gradient normals)", [], measure_steel),
    ("steel", "steel_pile.toml", "outline normals",
     [('normals = "mass_gradient"\nsurface = "pile surface"',
       'surfaces = { bottom = "tip", left = "inner", right = "outer" }')], measure_steel),
    ("incompressible", "incompressible_footing.toml", "nu = 0.49, B-bar", [], measure_footing),
    ("incompressible", "incompressible_footing.toml", "nu = 0.49, no B-bar",
     [("bbar = true", "bbar = false")], measure_footing),
    ("incompressible", "incompressible_footing.toml", "nu = 0.499, B-bar",
     [("poisson_ratio = 0.49", "poisson_ratio = 0.499")], measure_footing),
    ("incompressible", "incompressible_footing.toml", "nu = 0.499, no B-bar",
     [("poisson_ratio = 0.49", "poisson_ratio = 0.499"), ("bbar = true", "bbar = false")],
     measure_footing),
    ("confinement", "hs_high_confinement.toml", "10 MPa", [], measure_confinement),
    ("disc", "stiff_contact_block.toml", "E ratio 2.2e5", [], measure_disc),
    ("gdp", "gdp_torque.toml", "829 kN m/rad", [], measure_pile),
    ("gdp", "gdp_torque.toml", "8 290 kN m/rad (10 x)",
     [("amplitude = 829000.0", "amplitude = 8290000.0")], measure_pile),
    ("impact", "impact_x10.toml", "7 500 kN/rad (10 F_max)", [], measure_pile),
    ("surface", "free_surface_shaking.toml", "Hardening Soil", [], measure_none),
    ("collapse", "collapsing_column.toml", "Mohr-Coulomb, phi = 30 deg", [], measure_collapse),
])


def residuals(history):
    """Peak and final relative energy residual. The peak skips the rows whose energy in play is
    below 1 % of the run's largest: at the start of a run the energies are tiny and the residual,
    a start-up error of order dt, is a large fraction of them."""
    relative = history["energy/relative_residual"][:]
    residual = np.abs(history["energy/residual"][:])
    scale = np.where(relative > 0, residual / np.where(relative > 0, relative, 1.0), 0.0)
    significant = scale >= 0.01 * scale.max() if scale.max() > 0 else np.ones_like(scale, bool)
    return float(relative[significant].max()), float(relative[-1])


def run_row(mpile, threads, row, keep):
    group, case, setting, replacements, measure = row
    with open(os.path.join(ROOT, "cases", "stability", case)) as f:
        text = f.read()
    for old, new in replacements:
        if text.count(old) != 1:
            sys.exit(f"stability: '{old}' must occur once in cases/stability/{case}")
        text = text.replace(old, new)
    directory = tempfile.mkdtemp(prefix="mpile_stability_", dir=keep)
    path = os.path.join(directory, case)
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(directory, "out")
    start = time.monotonic()
    done = subprocess.run([mpile, "run", path, "--threads", str(threads), "--out", out],
                          capture_output=True, text=True)
    wall = time.monotonic() - start
    with h5py.File(os.path.join(out, "history.h5"), "r") as history:
        status = history.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else str(status)
        steps = int(history["step"][-1])
        # The first row is the initial state (dt 0); the last step is cut to land on the end.
        dt = history["dt"][1:-1] if len(history["dt"]) > 2 else history["dt"][1:]
        peak, final = residuals(history)
        # A run stopped before its first step has nothing to measure.
        measured = measure(history, out) if steps > 0 else ""
    if done.returncode == 0:
        outcome = "stable"
    else:
        outcome = "stopped: " + status.removeprefix("failed: ")
    return {
        "case": case, "setting": setting, "outcome": outcome, "steps": steps,
        "dt_start": float(dt[0]) if len(dt) else float("nan"),
        "dt_smallest": float(dt.min()) if len(dt) else float("nan"), "peak_residual": peak,
        "final_residual": final, "wall_seconds": wall, "threads": threads, "measured": measured,
    }


def markdown(results):
    lines = ["| case | setting | outcome | steps | dt first, smallest (s) | energy residual peak / end "
             "| wall (s) | measured |",
             "|---|---|---|---|---|---|---|---|"]
    def step_sizes(r):
        if math.isnan(r["dt_start"]):
            return "-"
        return f"{r['dt_start']:.3g}, {r['dt_smallest']:.3g}"

    for r in results:
        lines.append(
            f"| `{r['case']}` | {r['setting']} | {r['outcome']} | {r['steps']} | "
            f"{step_sizes(r)} | {100 * r['peak_residual']:.2g} % / "
            f"{100 * r['final_residual']:.2g} % | {r['wall_seconds']:.1f} | {r['measured']} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mpile", default=os.path.join(ROOT, "build", "release", "bin", "mpile"))
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--rows", nargs="*", help="groups to run (default: all): " +
                        ", ".join(sorted({row[0] for row in ROWS})))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "figures", "stability"))
    parser.add_argument("--keep", help="keep each run's outputs under this directory")
    parser.add_argument("--no-docs", action="store_true", help="do not rewrite docs/stability.md")
    args = parser.parse_args()
    rows = [row for row in ROWS if not args.rows or row[0] in args.rows]
    keep = args.keep or tempfile.mkdtemp(prefix="mpile_stability_")
    os.makedirs(keep, exist_ok=True)
    results = []
    for row in rows:
        result = run_row(args.mpile, args.threads, row, keep)
        print(f"{result['case']:28s} {result['setting']:34s} {result['outcome'][:70]:70s} "
              f"{result['wall_seconds']:7.1f} s", flush=True)
        results.append(result)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "stability.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(results[0].keys()))
        writer.writeheader()
        writer.writerows(results)
    table = markdown(results)
    print(table)
    if not args.no_docs and not args.rows:
        path = os.path.join(ROOT, "docs", "stability.md")
        with open(path) as f:
            text = f.read()
        if TABLE_START not in text or TABLE_END not in text:
            sys.exit("stability: docs/stability.md lacks the table markers")
        before = text[:text.index(TABLE_START) + len(TABLE_START)]
        after = text[text.index(TABLE_END):]
        with open(path, "w") as f:
            f.write(before + "\n" + table + "\n" + after)


if __name__ == "__main__":
    main()
