#!/usr/bin/python3
"""Write a synthetic mpile run directory whose values are known exactly, for the tests of
tools/plot_monopile.py and tools/render_sigma_ry.py.

  tests/make_monopile_history.py OUT_DIR

history.h5 has the layout of a real run: phase 0 holds the pile still at u_y = 0, phase 1 (the
installation) starts where phase 0's last row is and drives it down at 0.1 m/s for 5 s. With s = penetration / 0.1 m, the forces of the soil
on the pile are, in kN/rad,

  surface          F_r     F_y     F_theta
  tip              2 s     50 s    -4 s
  external_shaft  -20 s     8 s    -6 s
  internal_shaft   10 s     4 s    -3 s

so that |F_y| / |F_r| = 0.4 and sqrt(F_y^2 + F_theta^2) / |F_r| = 0.5 on both shafts. The pore
water carries 3/4 of each F_r and 1/2 of each F_y (pore_F_r, pore_F_y), and the excess pore
pressure at the monitors below_tip, inside_tip, outer_shaft_1m and outer_shaft_2m is -100, -50,
-20 and -10 kPa times s (tension positive: compressed). Row k is step 10 k at a wall time of k / 10 s.

particles.pvd lists two snapshots of a 50 x 50 lattice of soil particles (spacing 0.02 m) on
0 < r, y < 1 m with sigma_ry = 10 kPa/m * (r + y - 1 m) at t = 2.5 s (half of it at t = 0), around a
block of pile particles (body 1) on 0.4 < r < 0.6 m, 0.6 < y < 1 m with an absurd sigma_ry of 1e9 Pa,
which must never reach the colour scale.

Uses Debian's python3-h5py, python3-numpy and python3-vtk9.
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from point_snapshot import write_point_snapshot  # noqa: E402

FORCES_KN = {"tip": (2.0, 50.0, -4.0), "external_shaft": (-20.0, 8.0, -6.0),
             "internal_shaft": (10.0, 4.0, -3.0)}
RADIUS = {"tip": 2.0, "external_shaft": 2.05, "internal_shaft": 1.95}  # lever arms of M_theta [m]
MONITOR_EXCESS_KPA = {"below_tip": 100.0, "inside_tip": 50.0, "outer_shaft_1m": 20.0,
                      "outer_shaft_2m": 10.0}
SPEED = 0.1  # m/s
# The part of the case file the tools read: the phases, of which the installation is the last.
CASE_TEXT = """title = "synthetic monopile"
[[phases]]
name = "equilibrium"
duration = 0.5
[[phases]]
name = "installation"
duration = 5.0
"""
PHASE0_ROWS, PHASE1_ROWS, INTERVAL = 50, 501, 0.01  # rows, rows, s


def write_history(path):
    rows = PHASE0_ROWS + PHASE1_ROWS
    time = np.arange(rows) * INTERVAL
    phase = np.where(np.arange(rows) < PHASE0_ROWS, 0.0, 1.0)
    installing = phase == 1.0
    elapsed = np.where(installing, time - time[PHASE0_ROWS - 1], 0.0)
    penetration = SPEED * elapsed
    with h5py.File(path, "w") as history:
        history.attrs["title"] = "synthetic monopile"
        history.attrs["case_text"] = CASE_TEXT
        history.attrs["status"] = "complete"
        history.attrs["geometry"] = "axisymmetric: extensive quantities per radian"

        def dataset(name, values, unit):
            history.create_dataset(name, data=np.asarray(values, dtype=np.float64))
            history[name].attrs["unit"] = unit

        dataset("/time", time, "s")
        dataset("/phase", phase, "index into the case's [[phases]]")
        dataset("/bodies/pile/u_y", -penetration, "m")
        dataset("/bodies/pile/rotation", elapsed, "rad")
        dataset("/bodies/pile/angular_velocity", installing.astype(float), "rad/s")
        for surface, components in FORCES_KN.items():
            f_r, f_y, f_theta = (1e3 * component * penetration / 0.1 for component in components)
            # Large forces while the pile is held, which must not leak into the installation results.
            held = np.where(installing, 0.0, 1e6)
            dataset(f"/reactions/pile/{surface}/F_r", f_r + held, "N/rad")
            dataset(f"/reactions/pile/{surface}/F_y", f_y + held, "N/rad")
            dataset(f"/reactions/pile/{surface}/F_theta", f_theta, "N/rad")
            dataset(f"/reactions/pile/{surface}/M_theta", RADIUS[surface] * f_theta, "N m/rad")
            dataset(f"/reactions/pile/{surface}/pore_F_r", 0.75 * f_r, "N/rad")
            dataset(f"/reactions/pile/{surface}/pore_F_y", 0.5 * f_y, "N/rad")
        dataset("/step", 10.0 * np.arange(rows), "-")
        dataset("/wall_time", 0.1 * np.arange(rows), "s")
        for monitor, kpa in MONITOR_EXCESS_KPA.items():
            dataset(f"/monitors/{monitor}/excess_pore_pressure", -1e3 * kpa * penetration / 0.1, "Pa")


def write_snapshot(path, scale):
    centres = 0.01 + 0.02 * np.arange(50)
    r, y = (a.ravel() for a in np.meshgrid(centres, centres))
    pile = (r > 0.4) & (r < 0.6) & (y > 0.6)
    sigma_ry = np.where(pile, 1e9, scale * 1e4 * (r + y - 1.0))
    write_point_snapshot(path, r, y, {"sigma_ry": sigma_ry, "body": pile.astype(np.int32),
                                      "material": pile.astype(np.int32)}, "make_monopile_history")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    write_history(os.path.join(out, "history.h5"))
    snapshots = [(0.0, 0.5), (2.5, 1.0)]
    entries = []
    for index, (time, scale) in enumerate(snapshots):
        name = f"particles_{index:06d}.vtu"
        write_snapshot(os.path.join(out, name), scale)
        entries.append(f'    <DataSet timestep="{time:g}" group="" part="0" file="{name}"/>\n')
    with open(os.path.join(out, "particles.pvd"), "w") as pvd:
        pvd.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" '
                  'byte_order="LittleEndian">\n  <Collection>\n' + "".join(entries)
                  + "  </Collection>\n</VTKFile>\n")
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
