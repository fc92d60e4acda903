#!/usr/bin/python3
"""Plot datasets of an mpile history.h5 against time or against another dataset, to a PNG.

  tools/plot_history.py out/case/history.h5 --list
  tools/plot_history.py out/case/history.h5 /energy/kinetic /energy/elastic
  tools/plot_history.py out/case/history.h5 /boundaries/top_cap/M_theta --x /time --out torque.png

Reads the history with the mpile package (python/mpile); uses Debian's python3-h5py and
python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("history", help="history.h5 of an mpile run")
    parser.add_argument("datasets", nargs="*", help="datasets to plot (for example /energy/kinetic)")
    parser.add_argument("--x", default="/time", help="dataset on the horizontal axis (default /time)")
    parser.add_argument("--out", help="PNG file (default: next to the history, named after the first dataset)")
    parser.add_argument("--list", action="store_true", help="list the datasets with their units and exit")
    args = parser.parse_args()

    try:
        listed = {name: (units, length) for name, units, length in mpile.list_datasets(args.history)}
        if args.list or not args.datasets:
            for name, (units, length) in listed.items():
                print(f"{name} [{units}] ({length} values)")
            return 0
        for name in [args.x] + args.datasets:
            if name not in listed:
                print(f"plot_history: {args.history} has no dataset {name} (see --list)", file=sys.stderr)
                return 2
        for name in args.datasets:
            if listed[name][1] != listed[args.x][1]:
                print(f"plot_history: {name} has {listed[name][1]} values, {args.x} has {listed[args.x][1]}",
                      file=sys.stderr)
                return 2
        series = mpile.read_series(args.history, [args.x] + args.datasets)
        title = mpile.attributes(args.history).get("title", "")
    except mpile.RunFileError as error:
        print(f"plot_history: {error}", file=sys.stderr)
        return 2
    x = series[args.x]
    figure, axes = plt.subplots(figsize=(8, 5))
    for name in args.datasets:
        axes.plot(x, series[name], label=f"{name} [{listed[name][0]}]")
    axes.set_xlabel(f"{args.x} [{listed[args.x][0]}]")
    units = {listed[name][0] for name in args.datasets}
    axes.set_ylabel(", ".join(sorted(units)))
    axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend()
    out = args.out or args.history.rsplit("/", 1)[0] + "/" + args.datasets[0].strip("/").replace("/", "_") + ".png"
    figure.tight_layout()
    figure.savefig(out, dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # output piped into head and closed early
        sys.exit(0)
