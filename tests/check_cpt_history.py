#!/usr/bin/python3
"""Checks a CPT history's /cpt series against the standard cone's geometry (ISO 22476-1).

q_c must be the cone's F_y over pi R^2 (R^2 / 2 per radian) with R = 35.7 mm / 2, f_s the
sleeve's F_y over 2 pi R L (R L per radian) with L = 133.7 mm, R_f their ratio where q_c > 0,
and the cone's unit_end_resistance q_c again. The areas come from the cone's outline in the
engine and from these constants here, so a wrong area, a swapped surface or a stale row fails.
Both are exact for straight edges: the tolerance, 1e-12 relative, is round-off.

    check_cpt_history.py out/history.h5
"""
import sys

import h5py
import numpy as np

RADIUS = 0.0357 / 2.0
SLEEVE = 0.1337


def close(name, value, expected):
    scale = max(np.max(np.abs(expected)), 1e-300)
    error = np.max(np.abs(value - expected)) / scale
    print(f"{name}: largest relative difference {error:.2e}")
    return error <= 1e-12


def main(path):
    with h5py.File(path, "r") as f:
        cone = f["/reactions/cone/cone"]
        sleeve = f["/reactions/cone/sleeve"]
        q_c, f_s, r_f = f["/cpt/q_c"][:], f["/cpt/f_s"][:], f["/cpt/R_f"][:]
        ok = close("cone plan area", cone.attrs["plan_area"], RADIUS**2 / 2.0)
        ok &= close("sleeve side area", sleeve.attrs["side_area"], RADIUS * SLEEVE)
        ok &= close("q_c", q_c, cone["F_y"][:] / (RADIUS**2 / 2.0))
        ok &= close("f_s", f_s, sleeve["F_y"][:] / (RADIUS * SLEEVE))
        ok &= close("cone unit_end_resistance", cone["unit_end_resistance"][:], q_c)
        bearing = q_c > 0.0
        ok &= close("R_f", r_f[bearing], f_s[bearing] / q_c[bearing])
        ok &= bool(np.all(np.isnan(r_f[~bearing])))
        ok &= f["/cpt/q_c"].attrs["units"] == "Pa" and q_c.size == f["/time"].size > 10
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
