#!/usr/bin/python3
"""The results of `mpile sweep`: gathers them again (results.csv, results.nc) and plots gathered
quantities against a parameter.

  tools/plot_sweep.py out/sweeps/gdp_torque                           # results.png, every quantity
  tools/plot_sweep.py out/sweeps/gdp_torque --quantities time_to_10cm --out time.png
  tools/plot_sweep.py out/sweeps/gdp_torque --x monopile.drive.torque.frequency

Uses the mpile package (python/mpile/sweep.py; docs/sweeps.md).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from mpile import sweep  # noqa: E402
from mpile.files import RunFileError  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", help="the sweep's output directory")
    parser.add_argument("--quantities", help="gathered quantities to plot, comma separated (default: all)")
    parser.add_argument("--x", help="the parameter on the x axis (default: the one with the most values)")
    parser.add_argument("--out", help="the figure (default: <directory>/results.png)")
    args = parser.parse_args()
    try:
        sweep.gather(args.directory)
        quantities = args.quantities.split(",") if args.quantities else None
        figure = sweep.plot(args.directory, x=args.x, quantities=quantities)
    except (RunFileError, ValueError) as e:
        sys.exit(f"plot_sweep.py: {e}")
    out = args.out or os.path.join(args.directory, "results.png")
    figure.savefig(out, dpi=120)
    print(out)


if __name__ == "__main__":
    main()
