#!/usr/bin/python3
"""Draw the seed paper's figures 3 to 7 for several monopile installation runs, one line per run:

  fig3_radial_forces.png          F_r against penetration on the tip, external and internal shaft
  fig4_vertical_forces.png        F_y against penetration on the same three surfaces
  fig5_friction_ratio.png         |F_y| / |F_r| against penetration on the internal and external shaft
  fig6_total_friction_ratio.png   sqrt(F_y^2 + F_theta^2) / |F_r| on the same two shafts
  fig7_penetration.png            penetration against time since the start of the installation

  tools/plot_monopile.py out/jacked out/impact:"impact driven" out/torsion --out docs/figures
  tools/plot_monopile.py out/jacked --out /tmp/figures --table 0.1,0.3,0.6
  tools/plot_monopile.py out/jacked_paper out/impact_paper out/gdp_paper --out docs/figures --blow-interval 0.85

Only the rows of the last phase (the installation) are used; penetration is the pile's total
downward displacement (it is held still before), time counts from the start of the installation. Forces are those of the soil on the pile per radian of circumference (r outward, y up,
theta along the spin). Ratios are left out where |F_r| is below 1e-3 of its maximum over the
installation; the friction coefficient (--friction) is a wide light-grey dashed line beneath their
curves, which carry markers (a shape per run, at staggered penetrations), so that a curve lying on
it stays in view. --table prints, at the first row at or beyond each penetration, the forces (Fr, Fy,
Ft = F_theta) on the tip, external and internal shaft in kN/rad and the ratios Fy/Fr = |F_y| / |F_r|
and Fyt/Fr = sqrt(F_y^2 + F_theta^2) / |F_r| on both shafts, one line per run and penetration.

The runs are read by the mpile package (python/mpile/monopile.py), which users share;
uses Debian's python3-h5py, python3-numpy and python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import os
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from mpile.files import RunFileError  # noqa: E402
from mpile.monopile import COMPONENTS, installation, shaft_ratios, smoothed_ratios  # noqa: E402

CONVENTION = "force of the soil on the pile, per radian;\nr outward, y up"


def load(spec, body, surfaces, real_blow_interval=None):
    """The installation of the run named by RUN_DIR[:LABEL] (the label defaults to its title)."""
    directory, _, label = spec.partition(":")
    try:
        return installation(directory, body, surfaces, real_blow_interval, label or None)
    except RunFileError as error:
        sys.exit(f"plot_monopile: {error}")


def save(figure, path):
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
    print(path)


def force_figure(runs, component, symbol, surfaces, path):
    figure, axes = plt.subplots(1, len(surfaces), figsize=(4.2 * len(surfaces), 4.4), sharex=True)
    for ax, surface in zip(axes, surfaces):
        for index, run in enumerate(runs):
            ax.plot(run.penetration, run.forces[surface][component], color=f"C{index}", linewidth=0.8,
                    label=run.label)
        ax.set_title(surface.replace("_", " "))
        ax.set_xlabel("penetration [m]")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel(f"{symbol} [kN/rad]\n({CONVENTION})", fontsize=9)
    axes[0].legend(fontsize=8)
    save(figure, path)


# The ratio figures' line at the contact friction coefficient lies beneath the curves, wide and light,
# so that a curve lying exactly on it (a shaft sliding all along, F_y / F_r = mu) stays in view on
# top of it; each curve also carries its own marker, at staggered penetrations.
FRICTION_LINE = dict(color="0.6", linestyle="--", linewidth=2.2, zorder=1.5)
CURVE_ZORDER = 3.0
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "<", ">")
MARKS_PER_CURVE = 10


def mark_rows(penetration, index, count, marks=MARKS_PER_CURVE):
    """Rows at which to mark run `index` of `count`: the first at or beyond each of `marks` penetrations
    evenly spaced over its range, shifted by index / count of a spacing so that runs whose curves
    coincide still show each its own markers."""
    finite = np.isfinite(penetration)
    if not finite.any():
        return []
    low, high = np.min(penetration[finite]), np.max(penetration[finite])
    if high <= low:
        return [int(np.flatnonzero(finite)[0])]
    spacing = (high - low) / marks
    rows = []
    for target in low + spacing * (np.arange(marks) + (index + 0.5) / count):
        reached = np.flatnonzero(finite & (penetration >= target))
        if reached.size and (not rows or reached[0] != rows[-1]):
            rows.append(int(reached[0]))
    return rows


def draw_ratio_figure(runs, which, ylabel, shafts, friction, smooth):
    """The figure of one friction ratio against penetration on each shaft, not yet saved."""
    figure, axes = plt.subplots(1, len(shafts), figsize=(5.2 * len(shafts), 4.4), sharex=True, sharey=True)
    shown = []
    for ax, surface in zip(axes, shafts):
        for index, run in enumerate(runs):
            raw = shaft_ratios(run.forces[surface])[which]
            shown.append(raw)
            marks = dict(marker=MARKERS[index % len(MARKERS)], markersize=4.5,
                         markevery=mark_rows(run.penetration, index, len(runs)))
            ax.plot(run.penetration, raw, color=f"C{index}", linewidth=0.8 if smooth <= 0 else 0.6,
                    alpha=0.5 if smooth else 1.0, zorder=CURVE_ZORDER, label=run.label,
                    **(marks if smooth <= 0 else {}))
            if smooth > 0:
                ax.plot(run.penetration, smoothed_ratios(run.forces[surface], run.time, smooth)[which],
                        color=f"C{index}", linewidth=1.8, zorder=CURVE_ZORDER + 0.5,
                        label=f"{run.label}, running mean over {smooth:g} s", **marks)
        ax.axhline(friction, label=f"contact friction coefficient {friction:g}", **FRICTION_LINE)
        ax.set_title(surface.replace("_", " "))
        ax.set_xlabel("penetration [m]")
        ax.grid(True, alpha=0.3)
    # Where |F_r| is small but above the cut-off the ratios spike; scale the axis to the bulk of them.
    values = np.concatenate(shown)
    values = values[np.isfinite(values)]
    top = max(2.0 * friction, 1.1 * np.percentile(values, 99) if values.size else 0.0)
    axes[0].set_ylim(0.0, top if top > 0.0 else 1.0)
    axes[0].set_ylabel(f"{ylabel} [-]\n({CONVENTION})", fontsize=9)
    axes[0].legend(fontsize=8)
    figure.tight_layout()
    return figure


def ratio_figure(runs, which, ylabel, shafts, friction, smooth, path):
    save(draw_ratio_figure(runs, which, ylabel, shafts, friction, smooth), path)


def penetration_figure(runs, path):
    figure, ax = plt.subplots(figsize=(6.4, 4.4))
    for index, run in enumerate(runs):
        ax.plot(run.time, run.penetration, color=f"C{index}", linewidth=0.8, label=run.label)
    ax.set_xlabel("time since the start of the installation [s]")
    ax.set_ylabel("penetration [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    save(figure, path)


def number(value, decimals):
    """Fixed-point text without the sign of a value that rounds to zero ("0.000", not "-0.000")."""
    formatted = f"{value:.{decimals}f}"
    return formatted.lstrip("-") if float(formatted) == 0.0 else formatted


def print_table(runs, targets, surfaces):
    shafts = surfaces[1:]
    short = [surface[:3] for surface in surfaces]
    header = ["label", "penetration[m]", "time[s]"]
    header += [f"{name}_{component}[kN/rad]" for name in short for component in ("Fr", "Fy", "Ft")]
    header += [f"{name}_{ratio_name}" for name in short[1:] for ratio_name in ("Fy/Fr", "Fyt/Fr")]
    lines = [header]
    for run in runs:
        # Quoted when it has spaces, so that the table still splits on whitespace.
        label = f'"{run.label}"' if any(c.isspace() for c in run.label) else run.label
        for target in targets:
            row = run.index_at(target)
            if row is None:
                lines.append([label, f"{target:.4f}", "not reached"])
                continue
            cells = [label, number(run.penetration[row], 4), number(run.time[row], 4)]
            cells += [number(run.forces[s][c][row], 3) for s in surfaces for c in COMPONENTS]
            cells += [number(values[row], 4) for s in shafts for values in shaft_ratios(run.forces[s])]
            lines.append(cells)
    widths = [max(len(line[k]) for line in lines if k < len(line)) for k in range(len(header))]
    for line in lines:
        cells = [line[0].ljust(widths[0])] + [cell.rjust(width) for cell, width in zip(line[1:], widths[1:])]
        print("  ".join(cells).rstrip())


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", metavar="RUN_DIR[:LABEL]",
                        help="output directory of a run (or its history.h5); label default: its title")
    parser.add_argument("--out", required=True, help="directory for the PNG files")
    parser.add_argument("--friction", type=float, default=0.4,
                        help="contact friction coefficient, drawn dashed on the ratio figures (default 0.4)")
    parser.add_argument("--smooth", type=float, default=0.0, metavar="SECONDS",
                        help="also draw running means over this window on the ratio figures (default 0: off)")
    parser.add_argument("--table", type=lambda s: [float(x) for x in s.split(",")], metavar="PENETRATIONS",
                        help="comma-separated penetrations in m at which to print forces and ratios")
    parser.add_argument("--body", default="pile", help="the pile's body name (default pile)")
    parser.add_argument("--surfaces", default="tip,external_shaft,internal_shaft", metavar="TIP,EXTERNAL,INTERNAL",
                        help="the pile's contact surfaces (default tip,external_shaft,internal_shaft)")
    parser.add_argument("--blow-interval", type=float, metavar="SECONDS",
                        help="for runs driven by a pulse train (impact), draw blow k at k times this interval on the "
                             "time axis (the seed's 0.85 s when the run struck more often)")
    args = parser.parse_args()
    surfaces = args.surfaces.split(",")
    if len(surfaces) != 3:
        parser.error("--surfaces needs three names: tip, external shaft, internal shaft")

    runs = [load(spec, args.body, surfaces, args.blow_interval) for spec in args.runs]
    if args.table:
        print_table(runs, args.table, surfaces)
    os.makedirs(args.out, exist_ok=True)
    shafts = [surfaces[2], surfaces[1]]  # internal, external, as in the paper
    force_figure(runs, "F_r", "$F_r$", surfaces, os.path.join(args.out, "fig3_radial_forces.png"))
    force_figure(runs, "F_y", "$F_y$", surfaces, os.path.join(args.out, "fig4_vertical_forces.png"))
    ratio_figure(runs, 0, r"$|F_y| \,/\, |F_r|$", shafts, args.friction, args.smooth,
                 os.path.join(args.out, "fig5_friction_ratio.png"))
    ratio_figure(runs, 1, r"$\sqrt{F_y^2 + F_\theta^2} \,/\, |F_r|$", shafts, args.friction, args.smooth,
                 os.path.join(args.out, "fig6_total_friction_ratio.png"))
    penetration_figure(runs, os.path.join(args.out, "fig7_penetration.png"))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # output piped into head and closed early
        sys.exit(0)
