#!/usr/bin/python3
"""What a step local to each part of the mesh could save: each soil particle's crossing time h / c
(h its cell's smaller side, c its P-wave speed), grouped in levels of powers of two above the
smallest, and the particle updates per unit time of a multi-rate step (a particle of level k
stepping 2^k times the smallest step, up to a given number of levels) against one step for all.

Reads a run's last particle snapshot and its grid (`[output] grid_snapshots = true`) and the
case's Hardening Soil parameters (the only soil model it knows: E_ur = E_ur,ref ((c cos phi +
sigma_3 sin phi) / (c cos phi + p_ref sin phi))^m, floored as the model floors it). Velocities are
left out of c (in a pile's fine band they add a few per cent). The grid's own passes and the
levels' interfaces are not counted: an upper bound of what multi-rate stepping saves.

    tools/step_levels.py out/run [--material sand]
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from mpile.files import RunFileError  # noqa: E402
from mpile.history import case  # noqa: E402
from mpile.grid import open_grid_snapshots  # noqa: E402
from mpile.snapshots import open_snapshots  # noqa: E402


def unloading_constrained_modulus(material, sigma_3):
    """Hardening Soil's constrained modulus from E_ur at sigma_3 (compression positive, Pa)."""
    phi = math.radians(material["friction_angle"])
    c = material.get("cohesion", 0.0)
    ratio = np.maximum((c * math.cos(phi) + sigma_3 * math.sin(phi))
                       / (c * math.cos(phi) + material["p_ref"] * math.sin(phi)),
                       material.get("stiffness_floor", 0.01))
    young = material["eur_ref"] * ratio ** material["power"]
    nu = material["poisson_ur"]
    return young * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


def levels(crossing):
    """Each crossing time's level k: 2^k times the smallest at most."""
    return np.floor(np.log2(crossing / crossing.min())).astype(int)


def multirate_cost(level, top):
    """Particle updates of a multi-rate step with levels 0 to top (a particle above top steps at
    top's rate) per update of one step for all."""
    return float(np.sum(2.0 ** -np.minimum(level, top)) / level.size)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run", help="run directory with particles.pvd and grid.pvd")
    parser.add_argument("--material", default="sand")
    args = parser.parse_args()
    run = Path(args.run)
    try:
        material = case(run / "history.h5").get("materials", {}).get(args.material, {})
        if material.get("type") != "hardening_soil":
            raise RunFileError(f"{run}: material {args.material} is not hardening_soil")
        snapshot = open_snapshots(run)[-1]
        grid = open_grid_snapshots(run).at(snapshot.time)
    except (RunFileError, OSError) as e:
        print(f"step_levels.py: {e}", file=sys.stderr)
        return 2
    x_r, x_y = grid.r, grid.y
    a = snapshot.arrays
    names = snapshot.material_names
    soil = np.array([names[int(m)] == args.material for m in a["material"]])
    r, y = snapshot.positions[soil, 0], snapshot.positions[soil, 1]
    cell_r = np.clip(np.searchsorted(x_r, r) - 1, 0, len(x_r) - 2)
    cell_y = np.clip(np.searchsorted(x_y, y) - 1, 0, len(x_y) - 2)
    h = np.minimum(np.diff(x_r)[cell_r], np.diff(x_y)[cell_y])
    # The smallest principal compression of the r-y block and the hoop stress (theta shears left
    # out: none at K0, where the step is measured).
    block_minor = (-0.5 * (a["sigma_rr"][soil] + a["sigma_yy"][soil])
                   - np.hypot(0.5 * (a["sigma_rr"][soil] - a["sigma_yy"][soil]), a["sigma_ry"][soil]))
    sigma_3 = np.minimum(block_minor, -a["sigma_thth"][soil])
    constrained = unloading_constrained_modulus(material, sigma_3)
    crossing = h / np.sqrt(constrained / a["density"][soil])
    level = levels(crossing)
    print(f"{soil.sum()} particles of {args.material} at t = {snapshot.time:g} s; the smallest crossing time "
          f"{crossing.min():.3g} s (h = {h[crossing.argmin()]:.4g} m)")
    print("| level (step 2^k the smallest) | particles |")
    print("|---|---|")
    for k in range(level.max() + 1):
        print(f"| {k} | {(level == k).sum()} |")
    print()
    print("| levels | particle updates against one step for all | speed-up at most |")
    print("|---|---|---|")
    for top in sorted({1, 2, 3, int(level.max())}):
        cost = multirate_cost(level, top)
        print(f"| {top + 1} | {cost:.3f} | {1 / cost:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
