#!/usr/bin/python3
"""Ground vibration of installation runs as a Markdown table (docs/waves.md, "Ground vibration"):
per run the penetration gained, the energy radiated through absorbing faces (J/rad, and per metre
of penetration) and the peak particle velocity at each vibration monitor (mm/s).

  tools/vibration_table.py out/impact_quick out/gdp_quick:"GDP 414.5"

A run is a directory or history.h5, optionally with :label (default: the run's title). The
monitors are those named surface_* and tip_depth_* (the monopile cases' points at 2, 3 and 4 m),
or --monitors a,b,c.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))

import mpile  # noqa: E402
from mpile.files import RunFileError  # noqa: E402
from mpile.history import list_datasets  # noqa: E402


def vibration_monitors(path):
    names = {name.split("/")[2] for name, _, _ in list_datasets(path) if name.startswith("/monitors/")}
    return sorted(n for n in names if n.startswith(("surface_", "tip_depth_")))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="run directory or history.h5, optionally :label")
    parser.add_argument("--monitors", help="comma-separated monitor names")
    args = parser.parse_args()
    rows = []
    monitors = args.monitors.split(",") if args.monitors else None
    try:
        for run in args.runs:
            path, _, label = run.partition(":")
            chosen = monitors or vibration_monitors(mpile.files.history_path(path))
            rows.append(mpile.radiation(path, monitors=chosen, label=label or None))
            monitors = monitors or chosen
    except RunFileError as e:
        print(f"vibration_table: {e}", file=sys.stderr)
        return 2
    header = ["run", "penetration (m)", "radiated (J/rad)", "radiated per m (J/rad/m)"]
    header += [f"PPV {m} (mm/s)" for m in monitors]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        cells = [r.label, f"{r.penetration:.4f}", f"{r.radiated:.4g}", f"{r.radiated_per_metre:.4g}"]
        cells += [f"{1e3 * r.ppv[m]:.3g}" for m in monitors]
        print("| " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
