#!/usr/bin/python3
"""Plot datasets of an mpile history.h5 against time or against another dataset, to a PNG.

  tools/plot_history.py out/case/history.h5 --list
  tools/plot_history.py out/case/history.h5 /energy/kinetic /energy/elastic
  tools/plot_history.py out/case/history.h5 /boundaries/top_cap/M_theta --x /time --out torque.png

Uses Debian's python3-h5py and python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def datasets(history):
    names = []
    history.visititems(lambda name, obj: names.append("/" + name) if isinstance(obj, h5py.Dataset) else None)
    return names


def unit(history, name):
    value = history[name].attrs.get("unit", "")
    return value.decode() if isinstance(value, bytes) else str(value)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("history", help="history.h5 of an mpile run")
    parser.add_argument("datasets", nargs="*", help="datasets to plot (for example /energy/kinetic)")
    parser.add_argument("--x", default="/time", help="dataset on the horizontal axis (default /time)")
    parser.add_argument("--out", help="PNG file (default: next to the history, named after the first dataset)")
    parser.add_argument("--list", action="store_true", help="list the datasets with their units and exit")
    args = parser.parse_args()

    with h5py.File(args.history, "r") as history:
        names = datasets(history)
        if args.list or not args.datasets:
            for name in names:
                print(f"{name} [{unit(history, name)}] ({history[name].shape[0]} values)")
            return 0
        for name in [args.x] + args.datasets:
            if name not in names:
                print(f"plot_history: {args.history} has no dataset {name} (see --list)", file=sys.stderr)
                return 2
        x = history[args.x][:]
        figure, axes = plt.subplots(figsize=(8, 5))
        for name in args.datasets:
            y = history[name][:]
            if len(y) != len(x):
                print(f"plot_history: {name} has {len(y)} values, {args.x} has {len(x)}", file=sys.stderr)
                return 2
            axes.plot(x, y, label=f"{name} [{unit(history, name)}]")
        axes.set_xlabel(f"{args.x} [{unit(history, args.x)}]")
        units = {unit(history, name) for name in args.datasets}
        axes.set_ylabel(", ".join(sorted(units)))
        title = history.attrs.get("title", "")
        axes.set_title(title.decode() if isinstance(title, bytes) else title)
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
