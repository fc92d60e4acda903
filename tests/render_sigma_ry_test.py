#!/usr/bin/python3
"""tools/render_sigma_ry.py on a graded synthetic snapshot: the picture must read as a field.

  tests/render_sigma_ry_test.py OUT_DIR

The snapshot (written here, axisymmetric: volume = area * r per radian, no history.h5 beside it, so
the tool must tell the geometry from the particles) has a fine band (0.025 m particles) on
0 < r < 0.5 m, coarse particles (0.1 m) on 0.5 < r < 1.2 m and elongated ones (0.1 by 0.05 m) on
1.2 < r < 2 m, all on 0 < y < 2 m, and a thin rigid pile
wall (body 1, 0.01 m particles) on 0.30 < r < 0.32 m from y = 1.2 m up, with sigma_ry = 20 kPa/m *
(r - y) in the soil and 1e9 Pa in the pile. Checked:

- the soil's bounding box is covered: more than 99 % of its pixels carry a colour (points one fine
  spacing wide, as the tool drew them before, cover about a third of it: the coarse particles are
  four times further apart);
- r and y axes labelled in metres, a colour bar in kPa, symmetric about zero;
- the pile drawn in grey and its tip's depth (y = 1.2 m) found;
- red, blue, near-white and grey where the field and the pile put them, white above the soil.

Prints "all ok" at the end.
"""
import importlib.util
import os
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from point_snapshot import write_point_snapshot  # noqa: E402

TOOL = Path(__file__).resolve().parent.parent / "tools" / "render_sigma_ry.py"


def lattice(r0, r1, y0, y1, spacing, spacing_y=None):
    """Particles on a lattice and the square roots of their areas."""
    spacing_y = spacing_y or spacing
    r = np.arange(r0 + 0.5 * spacing, r1, spacing)
    y = np.arange(y0 + 0.5 * spacing_y, y1, spacing_y)
    rr, yy = np.meshgrid(r, y)
    return rr.ravel(), yy.ravel(), np.full(rr.size, np.sqrt(spacing * spacing_y))


def write_snapshot(path):
    parts = [lattice(0.0, 0.5, 0.0, 2.0, 0.025), lattice(0.5, 1.2, 0.0, 2.0, 0.1), lattice(1.2, 2.0, 0.0, 2.0, 0.1, 0.05)]
    r, y, side = (np.concatenate(a) for a in zip(*parts))
    in_wall = (r > 0.3) & (r < 0.32) & (y > 1.2)
    r, y, side = r[~in_wall], y[~in_wall], side[~in_wall]
    wall_r, wall_y, wall_side = lattice(0.30, 0.32, 1.2, 2.2, 0.01)
    body = np.concatenate([np.zeros(r.size, dtype=np.int32), np.ones(wall_r.size, dtype=np.int32)])
    r, y, side = np.concatenate([r, wall_r]), np.concatenate([y, wall_y]), np.concatenate([side, wall_side])
    sigma_ry = np.where(body == 1, 1e9, 2e4 * (r - y))
    volume = side**2 * r  # per radian
    write_point_snapshot(path, r, y, {"sigma_ry": sigma_ry, "volume": volume, "body": body},
                         "render_sigma_ry_test")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    snapshot = out / "graded_000000.vtu"
    write_snapshot(snapshot)

    spec = importlib.util.spec_from_file_location("render_sigma_ry", TOOL)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    png = out / "graded.png"
    args = tool.parse_arguments([str(snapshot), "--out", str(png), "--window", "0", "2", "0", "2.4",
                                 "--pile-body", "1"])
    picture = tool.render(args)
    picture.figure.savefig(png, dpi=tool.DPI)
    image = np.round(tool.plt.imread(png) * 255).astype(np.uint8)
    failures = []

    def check(condition, text):
        print(("ok    " if condition else "FAIL  ") + text)
        if not condition:
            failures.append(text)

    fraction, count = tool.coverage(image, picture)
    check(fraction > 0.99, f"soil coverage {fraction:.4f} of {count} pixels in the soil's bounding box > 0.99")
    box = picture.soil_box
    check(np.allclose(box, (0.0, 2.0, 0.0, 2.0)), f"soil's bounding box {box} is 0..2 m by 0..2 m")
    check(picture.axes.get_xlabel() == "r [m]", f"r axis labelled {picture.axes.get_xlabel()!r}")
    check(picture.axes.get_ylabel() == "y [m]", f"y axis labelled {picture.axes.get_ylabel()!r}")
    check(len(picture.axes.get_xticklabels()) > 1 and len(picture.axes.get_yticklabels()) > 1, "both axes have ticks")
    label = picture.colour_bar.ax.get_ylabel()
    check(label == "sigma_ry [kPa]", f"colour bar labelled {label!r}")
    norm = picture.colour_bar.mappable.norm
    check(norm.vmin < 0 < norm.vmax and abs(norm.vmin + norm.vmax) < 1e-9 * norm.vmax,
          f"colour range {norm.vmin:.4g} to {norm.vmax:.4g} kPa symmetric about zero (the pile's 1e6 kPa kept off)")
    tips = [line for line in picture.axes.get_lines() if np.allclose(line.get_ydata(), 1.2)]
    check(len(tips) == 1, "the pile's tip marked at y = 1.2 m")
    for (r, y), expected in (((1.95, 0.05), "red"), ((0.05, 1.95), "blue"), ((0.31, 1.8), "grey"),
                             ((0.9, 2.2), "white"), ((1.0, 1.0), "white")):
        row, column = picture.pixel(r, y)
        name = tool.colour_name(image[row, column])
        check(name == expected, f"pixel at ({r}, {y}) is {name}, expected {expected}")
    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("all ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
