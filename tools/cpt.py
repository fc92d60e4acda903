#!/usr/bin/python3
"""Cone resistance q_c, sleeve friction f_s and friction ratio R_f = f_s / q_c of a CPT run.

Reads a history.h5 of a CPT (cases/cpt/): q_c is the vertical force on the cone over its plan
area, pi R^2 (R^2 / 2 per radian); f_s the vertical force on the sleeve over its area, 2 pi R L
(R L per radian). A case with [output.cpt] has them in /cpt, with the areas from the cone's
outline; for a history without, they are computed from the surfaces "cone" and "sleeve" and the
standard cone's --radius and --sleeve. Prints them averaged over windows of penetration and
optionally writes a CSV of every row.

    tools/cpt.py out/history.h5 [--radius 0.01785] [--sleeve 0.1337] [--csv cpt.csv]
    tools/cpt.py out/history.h5 --expect-qc 0.10 2.0 4.0   # exit 1 unless q_c(0.10 m) in [2, 4] MPa
"""
import argparse
import sys
from pathlib import Path

import numpy as np

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402


def cpt_series(path, body, radius, sleeve):
    try:
        if mpile.attributes(path).get("geometry", "").split(":")[0] != "axisymmetric":
            sys.exit(f"{path}: a CPT history must be axisymmetric")
        names = {name for name, _, _ in mpile.list_datasets(path)}
        if f"/bodies/{body}/u_y" not in names:
            sys.exit(f"{path}: no rigid body '{body}' (--body)")
        if "/cpt/q_c" in names:
            f = mpile.read_series(path, [f"/bodies/{body}/u_y", "/cpt/q_c", "/cpt/f_s"])
            return -f[f"/bodies/{body}/u_y"], f["/cpt/q_c"], f["/cpt/f_s"]
        base = f"/reactions/{body}"
        for surface in ("cone", "sleeve"):
            if f"{base}/{surface}/F_y" not in names:
                sys.exit(f"{path}: no /cpt and no {base}/{surface}/F_y "
                         "(contact surfaces 'cone' and 'sleeve')")
        f = mpile.read_series(path, [f"/bodies/{body}/u_y", f"{base}/cone/F_y", f"{base}/sleeve/F_y"])
    except mpile.RunFileError as error:
        sys.exit(str(error))
    penetration = -f[f"/bodies/{body}/u_y"]
    q_c = f[f"{base}/cone/F_y"] / (radius * radius / 2.0)  # per radian: the plan area pi R^2 over 2 pi
    f_s = f[f"{base}/sleeve/F_y"] / (radius * sleeve)
    return penetration, q_c, f_s


def window(penetration, values, depth, half_width):
    inside = np.abs(penetration - depth) <= half_width
    return values[inside].mean() if inside.any() else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("history")
    parser.add_argument("--body", default="cone")
    parser.add_argument("--radius", type=float, default=0.0357 / 2.0, help="cone radius (m)")
    parser.add_argument("--sleeve", type=float, default=0.1337, help="sleeve length (m)")
    parser.add_argument("--step", type=float, default=0.05, help="penetration windows (m)")
    parser.add_argument("--csv", help="write every row: penetration, q_c, f_s, R_f")
    parser.add_argument("--expect-qc", nargs=3, type=float, metavar=("DEPTH", "LOW", "HIGH"),
                        help="exit 1 unless the mean q_c within a quarter window of DEPTH (m) "
                        "lies in [LOW, HIGH] MPa")
    args = parser.parse_args()
    penetration, q_c, f_s = cpt_series(args.history, args.body, args.radius, args.sleeve)
    diameter = 2.0 * args.radius
    half = args.step / 4.0
    print(f"{'penetration (m)':>16} {'(D)':>6} {'q_c (MPa)':>10} {'f_s (kPa)':>10} {'R_f (%)':>8}")
    for depth in np.arange(args.step, penetration.max() + 1e-9, args.step):
        qc = window(penetration, q_c, depth, half)
        fs = window(penetration, f_s, depth, half)
        print(f"{depth:16.3f} {depth / diameter:6.1f} {qc / 1e6:10.2f} {fs / 1e3:10.1f} "
              f"{100.0 * fs / qc:8.2f}")
    if args.csv:
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(q_c > 0.0, f_s / q_c, np.nan)
        np.savetxt(args.csv, np.column_stack([penetration, q_c, f_s, ratio]), delimiter=",",
                   header="penetration_m,q_c_Pa,f_s_Pa,R_f", comments="")
        print(args.csv)
    if args.expect_qc:
        depth, low, high = args.expect_qc
        qc = window(penetration, q_c, depth, half) / 1e6
        verdict = "within" if low <= qc <= high else "OUTSIDE"
        print(f"q_c at {depth} m: {qc:.3f} MPa, {verdict} [{low}, {high}]")
        return 0 if low <= qc <= high else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
