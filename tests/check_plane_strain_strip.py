#!/usr/bin/python3
"""The CPT chamber's plane-strain strip variant (docs/cpt.md, "The pile tip against the cone").

Writes it with cases/cpt/make_cases.py (2 cells per half-width, jacked 2 cm), runs it and checks:
- the case is accepted: on a fixed grid, since the moving mesh follows axisymmetric bodies only;
- the half strip stays on its plane of symmetry and does not turn, although the soil on its one
  side pushes it off that plane and turns it (the held DOFs take a force and a moment);
- the base's unit end resistance is its F_y per metre over the half-width, the strip's plan area.

usage: check_plane_strain_strip.py MPILE OUT_DIR
"""
import pathlib
import subprocess
import sys

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "cases" / "cpt"))
from make_cases import RADIUS  # noqa: E402  (m, the strip's half-width: the cone's radius)

mpile, out = sys.argv[1], pathlib.Path(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
case = out / "strip.toml"
subprocess.run(
    [sys.executable, str(HERE.parent / "cases" / "cpt" / "make_cases.py"), str(case), "2", "0.02",
     "flat=true", "moving=false", "geometry=plane_strain"],
    check=True,
)
subprocess.run([mpile, "run", str(case), "--threads", "2", "--out", str(out / "run")], check=True,
               stdout=subprocess.DEVNULL)

with h5py.File(out / "run/history.h5", "r") as f:
    body = f["bodies/cone"]
    pen = body["penetration"][:]
    held = {
        k: float(np.abs(body[k][:]).max()) for k in ("u_r", "v_r", "rotation", "angular_velocity")
    }
    # The soil beside the strip's one face: a push off the plane of symmetry and a moment of many
    # N m per metre at 2 cm (about 12 kN m/m at 15 cm in the documented run).
    push = float(np.abs(body["contact_F_r"][:]).max())
    moment = float(np.abs(body["contact_torque"][:]).max())
    base = f["reactions/cone/cone"]
    fy, q = base["F_y"][:], base["unit_end_resistance"][:]

failures = []
if pen[-1] < 0.02 - 1e-6:
    failures.append(f"the strip stopped at {pen[-1]} m, short of 0.02 m")
for key, value in held.items():
    if value != 0.0:  # prescribed at zero: exactly zero, or the hold is lost
        failures.append(f"{key} reached {value}: the half strip left its plane of symmetry")
if push < 100.0 or moment < 1.0:
    failures.append(f"contact F_r {push} N/m, moment {moment} N m/m: the holds carried nothing")
loaded = np.abs(fy) > 1.0
# Round-off only: q is F_y over the plan area, which for a strip is its half-width per metre.
if not loaded.any() or np.max(np.abs(q[loaded] * RADIUS - fy[loaded]) / np.abs(fy[loaded])) > 1e-12:
    failures.append("the base's unit end resistance is not its F_y over the half-width")
print("\n".join(failures) if failures else "ok")
sys.exit(1 if failures else 0)
