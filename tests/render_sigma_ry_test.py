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
- red, blue, near-white and grey where the field and the pile put them, white above the soil;
- the default colour range (the 99th percentile, 37 kPa) clips the field's -39.5 to 38.5 kPa: the
  colour bar's label says so.

A second snapshot, 20 x 20 particles (0.05 m) on 0 < r, y < 1 m with sigma_ry = 30 kPa/m * (r - y)
but -119 kPa at the bottom-left particle and 222 kPa at the top-right one, is drawn on four colour
ranges: -44.7..44.7, -10..300, -200..100 and -200..300 kPa. The colour bar must end in arrows on the
clipped sides only ("both", "min", "max", "neither": the corner of the bar's box beside an arrow's
tip stays white, beside a plain end it takes the bar's colour), its label must give the clipping and
the field's range ("clipped at +-44.7 kPa; field -119 to 222 kPa") or only the array where nothing
is clipped, and the two outliers must take the end colours.

Prints "all ok" at the end.
"""
import importlib.util
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


def write_clipped_snapshot(path):
    """A field of -28.5 to 28.5 kPa with one outlier at each end (-119 and 222 kPa)."""
    centres = 0.025 + 0.05 * np.arange(20)
    r, y = (a.ravel() for a in np.meshgrid(centres, centres))
    sigma_ry = 3e4 * (r - y)
    sigma_ry[np.argmin(r + y)] = -119e3
    sigma_ry[np.argmax(r + y)] = 222e3
    write_point_snapshot(path, r, y, {"sigma_ry": sigma_ry, "volume": 0.05**2 * r}, "render_sigma_ry_test")


# Colour range (kPa), the colour bar's extend and label, and whether an arrow ends it at the bottom
# and at the top.
CLIPPED_CASES = (
    ((-44.7, 44.7), "both", "sigma_ry [kPa], clipped at \u00b144.7 kPa;\nfield -119 to 222 kPa", True, True),
    ((-10.0, 300.0), "min", "sigma_ry [kPa], clipped at -10 kPa;\nfield -119 to 222 kPa", True, False),
    ((-200.0, 100.0), "max", "sigma_ry [kPa], clipped at 100 kPa;\nfield -119 to 222 kPa", False, True),
    ((-200.0, 300.0), "neither", "sigma_ry [kPa]", False, False),
)


def check_clipping(tool, out, check):
    snapshot = out / "clipped_000000.vtu"
    write_clipped_snapshot(snapshot)
    for (low, high), extend, label, arrow_below, arrow_above in CLIPPED_CASES:
        png = out / f"clipped_{low:g}_{high:g}.png"
        args = tool.parse_arguments([str(snapshot), "--out", str(png), "--window", "0", "1", "0", "1",
                                     "--range", f"{low:g}", f"{high:g}"])
        picture = tool.render(args)
        picture.figure.savefig(png, dpi=tool.DPI)
        image = np.round(tool.plt.imread(png) * 255).astype(np.uint8)
        where = f"range {low:g} to {high:g} kPa:"
        bar = picture.colour_bar
        check(bar.extend == extend, f"{where} colour bar extend {bar.extend!r}, expected {extend!r}")
        text = bar.ax.get_ylabel()
        check(text == label,
              f"{where} colour bar labelled {text!r}" + ("" if text == label else f", expected {label!r}"))
        # The bar's box (25 pixels right of the field, 22 wide, as tall as the field): its left
        # corners, 2 pixels in, are white beside an arrow's tip and coloured beside a plain end.
        column = picture.left + picture.columns + 25 + 2
        top, bottom = picture.height - picture.bottom - picture.rows + 2, picture.height - picture.bottom - 3
        for row, arrow, end in ((bottom, arrow_below, "bottom"), (top, arrow_above, "top")):
            name = tool.colour_name(image[row, column])
            expected = "white" if arrow else ("blue" if end == "bottom" else "red")
            check(name == expected, f"{where} the bar's {end} corner is {name}, expected {expected} "
                  f"({'an arrow' if arrow else 'a plain end'})")
        if extend == "both":
            for (r, y), expected in (((0.025, 0.025), "blue"), ((0.975, 0.975), "red")):
                row, column = picture.pixel(r, y)
                name = tool.colour_name(image[row, column])
                check(name == expected, f"{where} outlier at ({r}, {y}) is {name}, expected {expected}")
        tool.plt.close(picture.figure)


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
    expected = "sigma_ry [kPa], clipped at \u00b137 kPa;\nfield -39.5 to 38.5 kPa"
    check(label == expected,
          f"colour bar labelled {label!r}" + ("" if label == expected else f", expected {expected!r}"))
    check(picture.colour_bar.extend == "both", f"colour bar extend {picture.colour_bar.extend!r}, expected 'both'")
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
    tool.plt.close(picture.figure)
    check_clipping(tool, out, check)
    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("all ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
