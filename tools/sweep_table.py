#!/usr/bin/python3
"""A sweep's results as a Markdown table: one row per variant, its parameters then the gathered
quantities asked for, each optionally scaled and rounded.

    tools/sweep_table.py out/sweeps/gdp_torque_hypoplastic \\
        --column monopile.drive.torque.amplitude:1e-3:2 --column monopile.drive.torque.frequency \\
        --column time_to_10cm::3 --column tip_F_y_at_10cm:1e-3:2

A column is NAME[:SCALE[:DIGITS]]: a parameter or a gathered quantity of the sweep (its
results.csv, through mpile.open_sweep), multiplied by SCALE (default 1) and written with DIGITS
decimals (default 3 significant digits' worth: general format). A quantity a variant did not reach
(NaN) is written "-". The header is the names as given, or LABEL when a column is written
NAME:SCALE:DIGITS:LABEL. Uses the mpile package of this repository (python/) and pandas.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402


def parse_column(text):
    parts = text.split(":")
    name = parts[0]
    scale = float(parts[1]) if len(parts) > 1 and parts[1] else 1.0
    digits = int(parts[2]) if len(parts) > 2 and parts[2] else None
    label = parts[3] if len(parts) > 3 and parts[3] else name
    return name, scale, digits, label


def cell(value, scale, digits):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    value = float(value) * scale
    return f"{value:.{digits}f}" if digits is not None else f"{value:g}"


def table(frame, columns):
    """The Markdown lines of `frame` (a pandas DataFrame) for the parsed columns."""
    missing = [name for name, *_ in columns if name not in frame.columns]
    if missing:
        raise SystemExit(f"no column {', '.join(missing)} (the sweep has: "
                         f"{', '.join(map(str, frame.columns))})")
    lines = ["| " + " | ".join(label for *_, label in columns) + " |",
             "|" + "---|" * len(columns)]
    for _, row in frame.iterrows():
        lines.append("| " + " | ".join(cell(row[name], scale, digits)
                                       for name, scale, digits, _ in columns) + " |")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="the sweep's output directory")
    parser.add_argument("--column", action="append", required=True,
                        help="NAME[:SCALE[:DIGITS[:LABEL]]], in the table's order")
    args = parser.parse_args(argv)
    frame = mpile.open_sweep(args.directory, form="pandas")
    print("\n".join(table(frame, [parse_column(c) for c in args.column])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
