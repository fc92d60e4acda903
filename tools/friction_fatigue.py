#!/usr/bin/python3
"""Friction fatigue of runs that cycle a pile at fixed depth: sigma'_r / sigma'_r0 against cycles.

  tools/friction_fatigue.py out/gdp_cycles_quick out/gdp_cycles_quick_hypoplastic \
      --frequency 60 --plot docs/figures/friction_fatigue.png

Prints, for each run, a markdown table of the cycle means of the radial effective stress over its
value before cycling (mpile.friction_fatigue) at cycles 1, 2, 5, 10, 20, 40 and the last, one
column per monitor; --plot draws them against the cycle number, one panel per run, the shaft's
monitors (names starting "shaft_") as lines by depth and the others (further from the wall)
dashed. Uses Debian's python3-h5py, -numpy, -pandas and -matplotlib and the mpile package of this
repository (python/).
"""
import argparse
import sys
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPOSITORY / "python"))
import mpile  # noqa: E402
from mpile.files import RunFileError  # noqa: E402

SHOWN = (1, 2, 5, 10, 20, 40)


def table_text(label, table):
    rows = [n for n in SHOWN if n in table.index] + ([table.index[-1]] if table.index[-1] not in SHOWN else [])
    lines = [f"{label}:", "", "| cycle | " + " | ".join(table.columns) + " |",
             "|---|" + "---|" * len(table.columns)]
    for n in rows:
        lines.append(f"| {n} | " + " | ".join(f"{table.loc[n, c]:.3f}" for c in table.columns) + " |")
    return "\n".join(lines)


def plot(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(1, len(runs), figsize=(5.5 * len(runs), 4.2), sharey=True, squeeze=False)
    for axis, (label, table) in zip(axes[0], runs):
        for column in table.columns:
            style = "-" if column.startswith("shaft_") else "--"
            axis.plot(table.index, table[column], style, label=column)
        axis.axhline(1.0, color="grey", linewidth=0.5)
        axis.set_xscale("log")
        axis.set_xlabel("cycles N")
        axis.set_title(label, fontsize=9)
        axis.legend(fontsize=7)
    axes[0][0].set_ylabel("sigma'_r / sigma'_r0 (cycle mean)")
    figure.tight_layout()
    figure.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="run output directories (or history.h5 files)")
    parser.add_argument("--frequency", type=float, required=True, help="the load's frequency (Hz)")
    parser.add_argument("--phase", help="the cycling phase's name (default: the last phase)")
    parser.add_argument("--plot", help="write the figure here (PNG)")
    args = parser.parse_args()
    runs = []
    try:
        for run in args.runs:
            table = mpile.friction_fatigue(run, args.frequency, phase=args.phase)
            label = mpile.attributes(run).get("title", str(run))
            runs.append((label, table))
            print(table_text(label, table))
            print()
    except (RunFileError, ValueError) as error:
        print(f"friction_fatigue: {error}", file=sys.stderr)
        return 2
    if args.plot:
        plot(runs, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
