#!/usr/bin/python3
"""The soil ahead of a CPT cone, snapshot by snapshot: median mean stress p (kPa) and mean void
ratio (when the material has one) in bands of radius and of depth below the tip.

Reads a CPT run's particle snapshots (cases/cpt/; `[output] snapshot_penetrations`) and its
history.h5 for the cone's displacement. The tip's height at the start is --tip (the chamber cases'
2.2 - 0.3 m). What it shows: whether the sand the cone is about to meet still carries the chamber's
stress, and whether it has changed its density before the cone got there.

    tools/cpt_column.py out/cpt_run [--tip 1.9] [--body cone] [--snapshot -1]
"""
import argparse
import sys
from pathlib import Path

import numpy as np

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402

RADIUS = 0.0357 / 2.0  # m, the standard cone's
R_EDGES = [0.0, RADIUS, 2 * RADIUS, 4 * RADIUS, 6 * RADIUS, 0.2, 0.4, 0.6]
DEPTHS = [(0.05, 0.1), (0.1, 0.2), (0.2, 0.3), (0.3, 0.5), (0.5, 0.8)]


def table(snapshot, tip, out):
    a = snapshot.arrays
    names = snapshot.material_names
    rigid = np.array(["(rigid)" in names[int(m)] for m in a["material"]])
    soil = ~rigid
    r, y = snapshot.positions[soil, 0], snapshot.positions[soil, 1]
    p = -(a["sigma_rr"] + a["sigma_yy"] + a["sigma_thth"])[soil] / 3.0
    e = a["void_ratio"][soil] if "void_ratio" in a else None
    header = "below tip (m)" + "".join(
        f"{lo * 1e3:>7.0f}-{hi * 1e3:<5.0f}mm" for lo, hi in zip(R_EDGES[:-1], R_EDGES[1:]))
    print(header, file=out)
    for d0, d1 in DEPTHS:
        row = f"{d0:5.2f}-{d1:<7.2f}"
        for lo, hi in zip(R_EDGES[:-1], R_EDGES[1:]):
            m = (r >= lo) & (r < hi) & (y < tip - d0) & (y >= tip - d1)
            if not m.any():
                row += f"{'-':>15s}"
            elif e is None:
                row += f"{np.median(p[m]) / 1e3:>15.1f}"
            else:
                row += f"{np.median(p[m]) / 1e3:>7.1f} [{e[m].mean():.3f}]"
        print(row, file=out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="the run's output directory")
    parser.add_argument("--tip", type=float, default=1.9, help="the tip's height at the start (m)")
    parser.add_argument("--body", default="cone")
    parser.add_argument("--snapshot", type=int, action="append",
                        help="snapshot index (repeatable; default all)")
    args = parser.parse_args()
    run = Path(args.run)
    try:
        f = mpile.read_series(run / "history.h5", ["/time", f"/bodies/{args.body}/u_y"])
        snapshots = mpile.open_snapshots(run)
        chosen = [snapshots[i] for i in args.snapshot] if args.snapshot else list(snapshots)
        for s in chosen:
            u_y = float(np.interp(s.time, f["/time"], f[f"/bodies/{args.body}/u_y"]))
            print(f"t = {s.time:.4g} s, penetration {-u_y:.3f} m: p (kPa)"
                  + (" [void ratio]" if "void_ratio" in s.arrays else ""))
            table(s, args.tip + u_y, sys.stdout)
    except mpile.RunFileError as error:
        sys.exit(str(error))


if __name__ == "__main__":
    main()
