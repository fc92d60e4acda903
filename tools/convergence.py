#!/usr/bin/python3
"""Mesh convergence of pile forces: Richardson extrapolation with an error estimate, and the error
of each resolution against its run time.

Give the runs of one case at several resolutions, each as DIRECTORY:H with H the characteristic
cell size (m) of that run (for example the cell at the pile tip):

  tools/convergence.py out/w2:0.00795 out/w3:0.0053 out/w4:0.003975 --at 0.05,0.1
  tools/convergence.py out/quick:0.05 out/mid:0.035 out/paper:0.025 --at 0.1,0.3 \\
      --quantities tip_Fy,int_Fr,ext_Fr --csv study.csv --figure error_vs_time.png
  tools/convergence.py out/w2_c8+out/w2_c4+out/w2_c79:0.00795 out/w3_c8+out/w3_c4:0.0053 ...

Or a resolution sweep (docs/sweeps.md) whose variants set [monopile] wall_cells, each variant's H
the pile tip's cell (wall_thickness / wall_cells); given its sweep file, the tool runs it first
(what has finished is not rerun), which makes the whole study one command:

  tools/convergence.py --sweep cases/sweeps/jacked_resolution.toml --at 0.1,0.2,0.29

Runs joined by '+' before the ':H' are an ensemble at one resolution: runs of the same case that
differ only by a perturbation (the Courant number, the seeding). Where pile forces respond to
such perturbations (resolved pile walls: docs/resolution.md), one run's value is a draw, and the
ensemble's mean is the value, the standard deviation of its members' values (n - 1) the scatter,
and the sum of their wall times its cost.

For each quantity (SURFACE_COMPONENT: tip, ext or int, and Fr, Fy or Ft for the soil's force on the
pile in kN/rad, tip_qb for the tip's unit end resistance in MPa, or total_Fy for the soil's whole
axial force on the body, /bodies/<body>/contact_F_y, which the surfaces' F_y add up to; base_Fy for
tip plus internal shaft F_y, the load the annulus and the soil plug take together, which varies less
with the mesh than their split) and penetration, the value of each run is the mean over the
installation rows within --window of that penetration (default 10 mm: stick-slip makes pile forces
scatter by several per cent from row to row, so a single row is no value to extrapolate), and its
scatter the standard deviation there. The three finest runs give the observed order p of
f(h) = f0 + C h^p (the root of the ratio of successive differences, which allows any refinement
ratios) and the extrapolated f0; the error band is Roache's grid convergence index of the finest
run, 1.25 |f1 - f2| / ((h2 / h1)^p - 1). Where no order can be observed (the values oscillate
with refinement, or their differences do not shrink as h^p with p in [0.5, 4]), the table says
which. Where the three finest oscillate, there is nothing to extrapolate: the value is the finest
run's, its band half the range of the three (Stern et al. 2001's estimate for oscillatory
convergence), or the scatter where that is larger. Otherwise it takes p =
--order (default 1, the order of the contact and GIMP transfer) and widens the safety factor to 3,
as for two runs. Each run's error is then |f - f0|, plotted against its wall time (the history's
wall_time) on log-log axes, one line per quantity and penetration. Where the two finest runs differ
by less than the larger of their scatters, the table says so: the extrapolation then rests on noise,
and the honest statement is the scatter itself. If in addition no order is observed, the value given
is the finest run's, with the larger of the scatter and the finest two's difference as its band (no
extrapolation).

Uses Debian's python3-h5py, python3-numpy and python3-matplotlib (tools/setup.sh).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tomllib

import h5py
import numpy as np

SURFACES = {"tip": "tip", "ext": "external_shaft", "int": "internal_shaft"}
COMPONENTS = {"Fr": "F_r", "Fy": "F_y", "Ft": "F_theta"}
ORDER_RANGE = (0.5, 4.0)
SAFETY_THREE = 1.25  # Roache: three grids with an observed order
SAFETY_TWO = 3.0  # two grids, or an order that could not be observed


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def dataset(quantity, body):
    """The history datasets whose sum is a quantity, and the scale to its reported unit."""
    surface, _, component = quantity.partition("_")
    if quantity == "total_Fy":
        return [f"/bodies/{body}/contact_F_y"], 1e-3, "kN/rad"
    if quantity == "base_Fy":
        return [f"/reactions/{body}/tip/F_y", f"/reactions/{body}/internal_shaft/F_y"], 1e-3, "kN/rad"
    if surface not in SURFACES:
        sys.exit(f"convergence: unknown surface in '{quantity}' (tip, ext or int; total_Fy, base_Fy)")
    if component == "qb" and surface == "tip":
        return [f"/reactions/{body}/tip/unit_end_resistance"], 1e-6, "MPa"
    if component not in COMPONENTS:
        sys.exit(f"convergence: unknown component in '{quantity}' (Fr, Fy, Ft; tip_qb)")
    return [f"/reactions/{body}/{SURFACES[surface]}/{COMPONENTS[component]}"], 1e-3, "kN/rad"


def load(spec, quantities, depths, window, body, running=False):
    """One resolution, DIRECTORY:H or an ensemble DIR+DIR+...:H: its cell size, wall time,
    directory and {(quantity, depth): (value, scatter)}. An ensemble's value is its members' mean,
    its scatter the larger of their standard deviation and the members' own within-window scatter,
    its wall time the sum of theirs."""
    directories, separator, h = spec.rpartition(":")
    if not separator:
        sys.exit(f"convergence: give each run as DIRECTORY:H, got '{spec}'")
    return load_group(directories.split("+"), float(h), quantities, depths, window, body, running)


def load_group(directories, h, quantities, depths, window, body, running=False):
    """Runs at one cell size h: one run, or an ensemble whose mean is the value (load)."""
    members = [load_run(directory, quantities, depths, window, body, running)
               for directory in directories]
    label = "+".join(directories)
    if len(members) == 1:
        wall, values = members[0]
        return h, wall, label, values
    values = {}
    for key in members[0][1]:
        means = np.array([member[1][key][0] for member in members])
        within = max(member[1][key][1] for member in members)
        values[key] = (float(means.mean()), max(float(means.std(ddof=1)), within))
    return h, sum(member[0] for member in members), label, values


def load_run(directory, quantities, depths, window, body, running=False):
    """One run: its wall time and {(quantity, depth): (mean, standard deviation) of the rows
    within the window}. With `running`, a run still going is read at the depths it has passed
    (its rows there are final)."""
    if not directory:
        sys.exit("convergence: an empty run directory (two '+' in a row?)")
    path = directory if directory.endswith(".h5") else os.path.join(directory, "history.h5")
    if not os.path.isfile(path):
        sys.exit(f"convergence: no history {path}")
    values = {}
    with h5py.File(path, "r") as history:
        status = text(history.attrs.get("status", ""))
        if not status.startswith("complete") and not (running and status == "running"):
            sys.exit(f"convergence: {path} is not a complete run "
                     f"(status '{text(history.attrs.get('status', ''))}')")
        # The case as it ran (its base files merged); older histories hold only case_text.
        case = tomllib.loads(text(history.attrs.get("case_resolved", history.attrs["case_text"])))
        needed = ["/phase", f"/bodies/{body}/u_y"]
        for quantity in quantities:
            for name in dataset(quantity, body)[0]:
                if name not in history:
                    sys.exit(f"convergence: {path} has no dataset {name}")
                needed.append(name)
        # The rows every series has: a running writer extends its series one after another, so
        # one read between two of them finds some a row longer than others.
        count = min(len(history[name]) for name in needed)
        phase = history["/phase"][:count]
        rows = phase == len(case["phases"]) - 1  # the installation is the last phase
        penetration = -history[f"/bodies/{body}/u_y"][:count][rows]
        for quantity in quantities:
            names, scale, _ = dataset(quantity, body)
            series = sum(history[name][:count][rows] for name in names) * scale
            for depth in depths:
                near = np.abs(penetration - depth) <= window
                if running and status == "running" and penetration.max(initial=0.0) < depth + window:
                    sys.exit(f"convergence: {path} is still running and has not passed "
                             f"{depth} + {window} m yet (it is at {penetration.max(initial=0.0):.4f} m)")
                if not near.any():
                    sys.exit(f"convergence: {path} has no installation row within {window} m of "
                             f"{depth} m (it reached {penetration.max(initial=0.0):.4f} m)")
                values[(quantity, depth)] = (float(series[near].mean()),
                                             float(series[near].std()))
        # A running run has no wall time yet. The /wall_time series carries the whole run's across
        # restarts (the root attribute held only the last process's before the writer was mended).
        wall = float(history.attrs.get("wall_time", float("nan")))
        if math.isfinite(wall) and "wall_time" in history and len(history["wall_time"]) > 0:
            wall = max(wall, float(history["wall_time"][-1]))
    return wall, values


def tip_cell(case):
    """The cell size at the pile tip of a monopile case as it ran: the wall's thickness over the
    cells across it (docs/case-format.md, [monopile] wall_cells; its defaults where unset)."""
    if "monopile" not in case:
        return None
    monopile = case["monopile"]
    return monopile.get("wall_thickness", 0.0159) / monopile.get("wall_cells", 1)


def sweep_groups(target, mpile, cores, out, running):
    """The runs of a resolution sweep grouped by cell size: [(h, [run directory, ...])], finest
    first. A sweep file (.toml) is run first with `mpile sweep` (which runs only the variants that
    have not finished, docs/sweeps.md) unless `running`; a directory is a sweep's output. Variants
    at one cell size that differ in another parameter (the Courant number, say) are an ensemble."""
    if target.endswith(".toml"):
        directory = out or os.path.join("out", "sweeps", os.path.splitext(os.path.basename(target))[0])
        if not running:
            command = [mpile, "sweep", target, "--out", directory, "--cores", str(cores)]
            print("convergence: " + " ".join(command), flush=True)
            status = subprocess.run(command).returncode
            if status != 0:
                sys.exit(f"convergence: the sweep {target} did not finish (mpile sweep exit status "
                         f"{status}); its failed variants are listed above")
    else:
        directory = target
    record = os.path.join(directory, "sweep.toml")
    if not os.path.isfile(record):
        sys.exit(f"convergence: {directory} holds no sweep (no sweep.toml; run `mpile sweep` first)")
    with open(record, "rb") as f:
        variants = tomllib.load(f).get("variants", [])
    groups = {}
    for variant in variants:
        run = os.path.join(directory, "variants", variant["id"])
        path = os.path.join(run, "history.h5")
        if not os.path.isfile(path):
            if running:
                print(f"convergence: variant {variant['id']} has no history yet; left out",
                      file=sys.stderr)
                continue
            sys.exit(f"convergence: variant {variant['id']} has no history ({path})")
        with h5py.File(path, "r") as history:
            case = tomllib.loads(text(history.attrs.get("case_resolved",
                                                        history.attrs["case_text"])))
        h = tip_cell(case)
        if h is None:
            sys.exit(f"convergence: {path} is not a monopile case, so its cell size is not known; "
                     "give its runs as DIRECTORY:H")
        groups.setdefault(round(h, 12), []).append(run)
    return sorted(groups.items())


def oscillates(f):
    """Whether three values, finest first, change direction with refinement."""
    return len(f) >= 3 and (f[1] - f[0]) * (f[2] - f[1]) <= 0.0


def observed_order(h, f):
    """p of f = f0 + C h^p through three points (h[0] < h[1] < h[2]), or None where the differences
    change sign (no monotone convergence) or no p in ORDER_RANGE fits."""
    if oscillates(f):
        return None
    target = (f[2] - f[1]) / (f[1] - f[0])

    def residual(p):
        return (h[2] ** p - h[1] ** p) / (h[1] ** p - h[0] ** p) - target

    low, high = ORDER_RANGE
    if residual(low) * residual(high) > 0.0:
        return None
    for _ in range(200):  # bisection: the ratio grows monotonically with p
        middle = 0.5 * (low + high)
        if residual(low) * residual(middle) <= 0.0:
            high = middle
        else:
            low = middle
    return 0.5 * (low + high)


def extrapolate(h, f, fallback_order):
    """(f0, band, p, observed) from runs sorted finest first: Richardson on the two finest with the
    observed order of the three finest where there is one; where those oscillate, the finest value
    +- half their range (p NaN: an oscillating sequence has no order, and the fallback's
    extrapolation of the finest two's difference would run past the values, its band with it);
    else Richardson with the fallback order."""
    if oscillates(f[:3]):
        return f[0], 0.5 * (max(f[:3]) - min(f[:3])), float("nan"), False
    p = observed_order(h[:3], f[:3]) if len(h) >= 3 else None
    observed = p is not None
    if not observed:
        p = fallback_order
    ratio = (h[1] / h[0]) ** p - 1.0
    f0 = f[0] + (f[0] - f[1]) / ratio
    band = (SAFETY_THREE if observed else SAFETY_TWO) * abs(f[0] - f[1]) / ratio
    return f0, band, p, observed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="*",
                        help="DIRECTORY:H or an ensemble DIR+DIR+...:H, at least two resolutions")
    parser.add_argument("--sweep", help="a resolution sweep instead of runs: its sweep file (run "
                        "first with `mpile sweep`) or its output directory; each variant's h is "
                        "the pile tip's cell, [monopile] wall_thickness / wall_cells")
    parser.add_argument("--out", help="the sweep's output directory (default out/sweeps/<name>)")
    parser.add_argument("--cores", type=int, default=2, help="cores the sweep's runs share")
    parser.add_argument("--mpile", default=os.path.join(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), "build", "release", "bin", "mpile"), help="the mpile binary")
    parser.add_argument("--at", required=True, help="penetrations (m), comma-separated")
    parser.add_argument("--quantities", default="tip_Fy,tip_qb,ext_Fr,ext_Fy,int_Fr,int_Fy")
    parser.add_argument("--window", type=float, default=0.01,
                        help="m either side of a penetration averaged over")
    parser.add_argument("--order", type=float, default=1.0,
                        help="order assumed where none is observed")
    parser.add_argument("--body", default="pile")
    parser.add_argument("--csv", help="write the table")
    parser.add_argument("--figure", help="write error against wall time (PNG)")
    parser.add_argument("--running", action="store_true",
                        help="also read runs still going, at depths they have passed (the rows "
                             "there are final; no figure, their wall times are not)")
    args = parser.parse_args()
    if args.sweep and args.runs:
        sys.exit("convergence: give runs or --sweep, not both")
    quantities = [q for q in args.quantities.split(",") if q]
    depths = [float(d) for d in args.at.split(",") if d]
    if args.running and args.figure:
        sys.exit("convergence: --figure needs complete runs (a running run's wall time is not final)")
    if args.sweep:
        groups = sweep_groups(args.sweep, args.mpile, args.cores, args.out, args.running)
        runs = [load_group(directories, h, quantities, depths, args.window, args.body, args.running)
                for h, directories in groups]
    else:
        runs = sorted((load(spec, quantities, depths, args.window, args.body, args.running)
                       for spec in args.runs),
                      key=lambda run: run[0])
    if len(runs) < 2:
        sys.exit("convergence: give at least two resolutions")
    h = [run[0] for run in runs]
    if len(set(h)) != len(h):
        sys.exit("convergence: two runs have the same cell size")

    header = ["quantity", "unit", "penetration_m"] + [f"h={x:g}" for x in h]
    header += ["order", "observed", "extrapolated", "error_band", "scatter"]
    header += [f"error h={x:g}" for x in h]
    table = []
    for quantity in quantities:
        unit = dataset(quantity, args.body)[2]
        for depth in depths:
            f = [run[3][(quantity, depth)][0] for run in runs]
            scatter = max(run[3][(quantity, depth)][1] for run in runs[:2])
            f0, band, p, observed = extrapolate(h, f, args.order)
            if oscillates(f):
                # Half the range, but not below the noise one run's value carries.
                band = max(band, scatter)
            elif not observed and abs(f[0] - f[1]) < scatter:
                # No order, and the finest two apart by less than the noise: extrapolating that
                # difference would amplify noise. The finest run is the value, its error the
                # larger of the scatter and the difference.
                f0, band = f[0], max(scatter, abs(f[0] - f[1]))
            table.append([quantity, unit, depth] + f + [p, observed, f0, band, scatter]
                         + [abs(x - f0) for x in f])

    print("  ".join(f"{name}" for name in header[:3] + header[3:3 + len(h)]
                    + ["p", "f0 +- band", "scatter"]))
    for row in table:
        values = "  ".join(f"{x:.4g}" for x in row[3:3 + len(h)])
        p, observed, f0, band, scatter = row[3 + len(h):8 + len(h)]
        # Oscillating runs have their own line below; what else leaves no order is said here.
        reason = ("two runs" if len(h) < 3 else
                  f"differences shrink as no h^p, {ORDER_RANGE[0]:g} <= p <= {ORDER_RANGE[1]:g}")
        within = abs(row[3] - row[4]) < scatter
        if observed:
            order = f"{p:.2f}"
        elif oscillates(row[3:3 + len(h)]):
            order = ("none (oscillates with refinement; the finest run's value +- half the "
                     "three's range or the scatter)")
        elif within:
            order = f"none ({reason}; the finest run's value, not extrapolated)"
        else:
            order = f"{p:g} (assumed: {reason})"
        noise = "  (the finest two differ by less than it)" if within else ""
        print(f"{row[0]}  {row[1]}  {row[2]:g}  {values}  {order}  {f0:.4g} +- {band:.2g}  "
              f"{scatter:.2g}{noise}")
    print("wall time (s): " + "  ".join(f"h={x:g}: {run[1]:.0f}" for x, run in zip(h, runs)))

    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(header)
            writer.writerows(table)
        print(args.csv)
    if args.figure:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        figure, axes = plt.subplots(figsize=(6.5, 4.5))
        wall = [run[1] for run in runs]
        for row in table:
            errors = row[8 + len(h):]
            # A run that is the value itself (no order, within the scatter) has no error to draw.
            relative = [e / abs(row[5 + len(h)]) if row[5 + len(h)] and e > 0.0 else math.nan
                        for e in errors]
            axes.loglog(wall, relative, "o-", label=f"{row[0]} at {row[2]:g} m")
        axes.set_xlabel("wall time (s)")
        axes.set_ylabel("|f - f0| / |f0|")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=7)
        figure.tight_layout()
        figure.savefig(args.figure, dpi=120)
        print(args.figure)
    return 0


if __name__ == "__main__":
    sys.exit(main())
