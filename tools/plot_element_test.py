#!/usr/bin/python3
"""Plot the CSVs of `mpile element-test` to one PNG: q against eps_1, eps_v against eps_1 and
sigma_1 against eps_1 (compression positive, strains in %, stresses in kPa), one curve per file.

  tools/plot_element_test.py out/mohr_coulomb_triaxial.csv
  tools/plot_element_test.py a.csv b.csv --out compare.png --labels "phi 30" "phi 35"

Uses Debian's python3-numpy and python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = ("eps_1", "eps_v", "sigma_1", "q")


def read(path):
    """The columns of one CSV by name, as float arrays."""
    try:
        data = np.genfromtxt(path, delimiter=",", names=True, ndmin=1)
    except (OSError, ValueError) as error:
        raise ValueError(f"{path}: cannot read ({error})")
    if data.dtype.names is None:
        raise ValueError(f"{path}: no header line")
    missing = [name for name in COLUMNS if name not in data.dtype.names]
    if missing:
        raise ValueError(f"{path}: no column {', '.join(missing)} (is it an mpile element-test CSV?)")
    return data


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="CSV files written by mpile element-test")
    parser.add_argument("--out", help="PNG file (default: next to the first CSV, same name)")
    parser.add_argument("--labels", nargs="+", help="legend entries, one per CSV (default: file names)")
    args = parser.parse_args()
    if args.labels and len(args.labels) != len(args.csv):
        print(f"plot_element_test: {len(args.labels)} labels for {len(args.csv)} files", file=sys.stderr)
        return 2
    try:
        tables = [read(path) for path in args.csv]
    except ValueError as error:
        print(f"plot_element_test: {error}", file=sys.stderr)
        return 2
    labels = args.labels or [os.path.splitext(os.path.basename(path))[0] for path in args.csv]

    figure, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    panels = (("q", "deviator stress q [kPa]", 1e-3),
              ("eps_v", "volumetric strain eps_v [%] (compression +)", 100.0),
              ("sigma_1", "vertical stress sigma_1 [kPa]", 1e-3))
    for data, label in zip(tables, labels):
        for axis, (name, _, factor) in zip(axes, panels):
            axis.plot(100.0 * data["eps_1"], factor * data[name], label=label)
    for axis, (_, title, _) in zip(axes, panels):
        axis.set_xlabel("axial strain eps_1 [%] (compression +)")
        axis.set_ylabel(title)
        axis.grid(True, alpha=0.3)
    axes[0].legend()
    figure.tight_layout()
    out = args.out or os.path.splitext(args.csv[0])[0] + ".png"
    figure.savefig(out, dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
