#!/usr/bin/python3
"""Render a stress field of one mpile particle snapshot to a PNG, as a field on the r-y plane (r to
the right, y up, both in m): each particle is painted over its own domain on a raster one image
pixel fine, so the soil is covered without gaps whatever its particles' sizes; the colours are
ParaView's "Cool to Warm" diverging map, symmetric about zero, in kPa, with a colour bar.

  tools/render_sigma_ry.py out/jacked/particles.pvd --out sigma_ry.png --time 2.0 --pile-body 3
  tools/render_sigma_ry.py out/jacked/particles_000004.vtu --out zoom.png --window 0 10 20 35 --range -50 50

A particle's domain is a rectangle of its area, volume / r in an axisymmetric run (volume is per
radian) or volume in plane strain (per metre), shaped like its spacing to its neighbours along r and
along y (a graded mesh's cells are elongated; a thin pile wall is one particle across). The geometry is read from the run's history.h5 beside
the snapshot, else told by --geometry, else guessed from the particles' spacing; a snapshot without
volumes gives every particle the median spacing of its neighbours. Larger particles are painted
first, so that the fine band's detail stays on top.

The colour range defaults to +/- the 99th percentile of |value| inside the window; values beyond it
take the end colours, and the colour bar then ends in arrows on the clipped side(s) and its label
gives the clipping and the field's own range in the window ("clipped at +-44.7 kPa; field -119 to
222 kPa"). The rigid pile's particles can be left out (--exclude-body) or drawn in grey over their
domains with their outline and the tip's depth marked (--pile-body) so they stay off the scale.
--check-pixel R Y prints the colour of the image at the physical point (r, y): red, light red,
white, light blue, blue, grey (pile) or other. --coverage prints the fraction of the image's pixels
inside the soil's bounding box (its particles' domains, within the window) that carry a colour.

Reads snapshots and picks the colour range with the mpile package (python/mpile); draws with
matplotlib (Agg, no display needed); uses Debian's python3-vtk9, python3-numpy and
python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap, TwoSlopeNorm, Normalize  # noqa: E402

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from mpile.display import particle_spacing, symmetric_bound  # noqa: E402
from mpile.files import RunFileError  # noqa: E402
from mpile.snapshots import open_snapshots, read_vtu  # noqa: E402

DPI = 100
LEFT_PIXELS = 90  # band at the left of the image for the y axis' ticks and label
BOTTOM_PIXELS = 60  # band at the bottom for the r axis' ticks and label
BAR_PIXELS = 170  # band at the right of the image kept for the colour bar
TITLE_PIXELS = 40  # band at the top of the image kept for the title
PILE_GREY = 0.5
BACKGROUND = (1.0, 1.0, 1.0)
# ParaView's "Cool to Warm" (Moreland's diverging map): its ends and near-white middle; matplotlib's
# "coolwarm" is the same map sampled finely, used between the ends.
COOL, MIDDLE, WARM = (0.231373, 0.298039, 0.752941), (0.865, 0.865, 0.865), (0.705882, 0.0156863, 0.14902)
# A pixel belongs to a particle's domain when its centre is within half the domain's side (plus this
# slack, which closes the seams a deformed, no longer exactly tiling set of domains leaves).
DOMAIN_SLACK = 1.05


def snapshot(path, time):
    """The .vtu to read and its simulated time (None for a bare .vtu): with a .pvd, the snapshot whose
    timestep is closest to `time`, or the last one when `time` is None."""
    if not path.endswith(".pvd"):
        return path, None
    snapshots = open_snapshots(path)
    if not snapshots:
        sys.exit(f"render_sigma_ry: {path} lists no snapshots")
    chosen = snapshots[-1] if time is None else snapshots.at(time)
    return str(chosen.path), chosen.time


def read_point_arrays(path):
    if not os.path.isfile(path):
        sys.exit(f"render_sigma_ry: no file {path}")
    xy, arrays, _ = read_vtu(path)
    if len(xy) == 0:
        sys.exit(f"render_sigma_ry: {path} has no particles")
    return xy, arrays


def run_geometry(snapshot_path):
    """"axisymmetric" or "plane" from the history.h5 of the run the snapshot belongs to, or None."""
    history = Path(snapshot_path).resolve().parent / "history.h5"
    if not history.is_file():
        return None
    try:
        import h5py

        with h5py.File(history, "r") as file:
            text = file.attrs.get("geometry")
    except (ImportError, OSError):
        return None
    if isinstance(text, bytes):
        text = text.decode()
    if not isinstance(text, str):
        return None
    return "axisymmetric" if text.startswith("axisymmetric") else "plane" if text.startswith("plane") else None


def domain_sides(xy, arrays, geometry):
    """Square root (m) of each particle's domain area, and the geometry it was worked out for."""
    spacing = particle_spacing(xy)
    if "volume" not in arrays:
        return np.full(len(xy), spacing), "no volume array: one neighbour spacing"
    volume = np.asarray(arrays["volume"], dtype=float)
    radius = np.maximum(np.abs(xy[:, 0]), 1e-12)
    if geometry is None:
        # The area whose side is nearer the neighbours' spacing (a factor of r, whole metres, apart).
        sample = slice(None, None, max(1, len(xy) // 200))
        axisymmetric = np.median(np.sqrt(volume[sample] / radius[sample]))
        plane = np.median(np.sqrt(volume[sample]))
        geometry = "axisymmetric" if abs(np.log(axisymmetric / spacing)) <= abs(np.log(plane / spacing)) else "plane"
    area = volume / radius if geometry == "axisymmetric" else volume
    return np.sqrt(np.maximum(area, 0.0)), geometry


def spacings_along_axes(xy, chunk=512):
    """Each particle's distance to its nearest neighbour along r (|dr| > |dy|) and along y (|dy| >
    |dr|), inf where it has none; brute force in chunks (the particles of one picture)."""
    n = len(xy)
    along_r, along_y = np.full(n, np.inf), np.full(n, np.inf)
    for start in range(0, n, chunk):
        d_r = np.abs(xy[start:start + chunk, None, 0] - xy[None, :, 0])
        d_y = np.abs(xy[start:start + chunk, None, 1] - xy[None, :, 1])
        along_r[start:start + chunk] = np.where(d_r > d_y, d_r, np.inf).min(axis=1)
        along_y[start:start + chunk] = np.where(d_y > d_r, d_y, np.inf).min(axis=1)
    return along_r, along_y


def domain_halves(xy, sides):
    """Half sizes (along r, along y) of rectangles of the domains' areas (sides**2) shaped like the
    particles' spacings along r and y, so that a graded mesh's elongated cells are tiled too."""
    if len(xy) < 2:
        return 0.5 * sides, 0.5 * sides
    along_r, along_y = spacings_along_axes(xy)
    area = sides**2
    both = np.isfinite(along_r) & np.isfinite(along_y)
    aspect = np.ones(len(xy))
    aspect[both] = np.clip(along_r[both] / along_y[both], 1.0 / 16.0, 16.0)
    side_r, side_y = np.sqrt(area * aspect), np.sqrt(area / aspect)
    # One row or column of particles (a thin wall): the spacing it has sets that side, the area the other.
    only_y = ~np.isfinite(along_r) & np.isfinite(along_y)
    side_y[only_y] = along_y[only_y]
    side_r[only_y] = area[only_y] / along_y[only_y]
    only_r = np.isfinite(along_r) & ~np.isfinite(along_y)
    side_r[only_r] = along_r[only_r]
    side_y[only_r] = area[only_r] / along_r[only_r]
    return 0.5 * side_r, 0.5 * side_y


def paint(raster, kind, xy, halves, values, label, r0, y0, pixel):
    """Paint each particle's domain (value and kind; `halves` its half sizes along r and y) into the
    rasters (row 0 at y0, column 0 at r0, `pixel` m square); largest domains first, so smaller ones
    stay on top."""
    rows, columns = raster.shape
    half_r, half_y = DOMAIN_SLACK * halves[0], DOMAIN_SLACK * halves[1]
    c0 = np.clip(np.ceil((xy[:, 0] - half_r - r0) / pixel - 0.5), 0, columns).astype(int)
    c1 = np.clip(np.floor((xy[:, 0] + half_r - r0) / pixel - 0.5) + 1, 0, columns).astype(int)
    w0 = np.clip(np.ceil((xy[:, 1] - half_y - y0) / pixel - 0.5), 0, rows).astype(int)
    w1 = np.clip(np.floor((xy[:, 1] + half_y - y0) / pixel - 0.5) + 1, 0, rows).astype(int)
    # A domain narrower than a pixel still colours the pixel its centre is in.
    centre_c = np.floor((xy[:, 0] - r0) / pixel).astype(int)
    centre_w = np.floor((xy[:, 1] - y0) / pixel).astype(int)
    c0, c1 = np.minimum(c0, centre_c), np.maximum(c1, centre_c + 1)
    w0, w1 = np.minimum(w0, centre_w), np.maximum(w1, centre_w + 1)
    c0, c1 = np.clip(c0, 0, columns), np.clip(c1, 0, columns)
    w0, w1 = np.clip(w0, 0, rows), np.clip(w1, 0, rows)
    for i in np.argsort(-(half_r * half_y), kind="stable"):
        if c1[i] > c0[i] and w1[i] > w0[i]:
            raster[w0[i]:w1[i], c0[i]:c1[i]] = values[i]
            kind[w0[i]:w1[i], c0[i]:c1[i]] = label


def diverging_map(low, high):
    """Cool to Warm from `low` (blue) to `high` (red), near-white at zero when the range spans it (so
    that the colour tells the sign even for an asymmetric --range), else midway."""
    colours = LinearSegmentedColormap.from_list(
        "cool_to_warm", [COOL] + [tuple(c[:3]) for c in plt.get_cmap("coolwarm")(np.linspace(0.05, 0.95, 19))]
        + [WARM], N=256)
    norm = TwoSlopeNorm(0.0, low, high) if low < 0.0 < high else Normalize(low, high)
    return colours, norm


def clipped_ends(field, low, high):
    """Matplotlib's colour bar `extend` for a field of range `field` (kPa) drawn on low..high: the
    ends beyond which some values were drawn in the end colours ("neither", "min", "max", "both")."""
    below, above = field[0] < low, field[1] > high
    return "both" if below and above else "min" if below else "max" if above else "neither"


def kpa(value):
    """A value in kPa to three significant digits, without an exponent: 44.7, -119, 222, 0.0123."""
    return f"{value:.0f}" if abs(value) >= 100.0 else f"{value:.3g}"


def bar_label(array, field, low, high):
    """The colour bar's label: the array and its unit and, where the colour range is narrower than
    the field, the clipped end(s) and the field's own range, so that the picture says it is clipped."""
    ends = clipped_ends(field, low, high)
    if ends == "neither":
        return f"{array} [kPa]"
    if ends == "both":
        at = f"\u00b1{kpa(high)}" if np.isclose(low, -high) else f"{kpa(low)} and {kpa(high)}"
    else:
        at = kpa(low if ends == "min" else high)
    return f"{array} [kPa], clipped at {at} kPa;\nfield {kpa(field[0])} to {kpa(field[1])} kPa"


def colour_name(rgb):
    """Red and blue are the outer ~30 % of each half of the map; light red and light blue are nearer
    the middle, so a value drawn at the wrong place or with the wrong scale reads differently."""
    r, g, b = (int(c) for c in rgb[:3])
    if max(r, g, b) - min(r, g, b) < 30:
        return "white" if min(r, g, b) > 200 else "grey"
    if r > g + 120 and r > b + 120:
        return "red"
    if b > r + 120:
        return "blue"
    if r > b + 30:
        return "light red"
    if b > r + 30:
        return "light blue"
    return "other"


def parse_arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", help="particles.pvd or one particles_NNNNNN.vtu of an mpile run")
    parser.add_argument("--out", required=True, help="PNG file")
    when = parser.add_mutually_exclusive_group()
    when.add_argument("--time", type=float, help="with a .pvd: the snapshot closest to this time in s")
    when.add_argument("--last", action="store_true", help="with a .pvd: the last snapshot (the default)")
    parser.add_argument("--array", default="sigma_ry", help="point array to show, in Pa (default sigma_ry)")
    parser.add_argument("--range", type=float, nargs=2, metavar=("LOW", "HIGH"),
                        help="colour range in kPa (default +/- the 99th percentile of |value| in the window)")
    parser.add_argument("--window", type=float, nargs=4, metavar=("R0", "R1", "Y0", "Y1"),
                        help="region to show in m (default: all particles)")
    parser.add_argument("--exclude-body", type=int, nargs="+", default=[], metavar="N",
                        help="leave out the particles of these body indices")
    parser.add_argument("--pile-body", type=int, metavar="N",
                        help="draw this body's particles in grey, with their outline and the tip's depth")
    parser.add_argument("--geometry", choices=("axisymmetric", "plane"),
                        help="how volume relates to area (default: from the run's history.h5, else guessed)")
    parser.add_argument("--title", help="title text (default: the array, the time and the window)")
    parser.add_argument("--size", type=int, nargs=2, metavar=("W", "H"),
                        help="image size in pixels (default 1000 wide, height to fit the window)")
    parser.add_argument("--check-pixel", type=float, nargs=2, action="append", default=[], metavar=("R", "Y"),
                        help="print the colour of the image at the physical point (r, y); repeatable")
    parser.add_argument("--coverage", action="store_true",
                        help="print the fraction of pixels in the soil's bounding box that carry a colour")
    args = parser.parse_args(argv)
    if args.window and not (args.window[0] < args.window[1] and args.window[2] < args.window[3]):
        parser.error("--window needs R0 < R1 and Y0 < Y1")
    return args


class Picture:
    """The figure drawn and where the window's points land in the image (pixels, row 0 at the top)."""

    def __init__(self, figure, axes, colour_bar, height, left, bottom, pixels_per_metre, r0, y0):
        self.figure, self.axes, self.colour_bar = figure, axes, colour_bar
        self.height, self.left, self.bottom = height, left, bottom
        self.pixels_per_metre, self.r0, self.y0 = pixels_per_metre, r0, y0
        self.soil_box = None  # (r0, r1, y0, y1) of the soil's domains inside the window

    def pixel(self, r, y):
        """(row from the top, column) of the image pixel at the physical point (r, y): from the
        intended layout, not from matplotlib's transforms, so that a wrong view shows up."""
        column = self.left + (r - self.r0) * self.pixels_per_metre
        row = self.height - 1 - (self.bottom + (y - self.y0) * self.pixels_per_metre)
        return int(np.floor(row + 0.5)), int(np.floor(column))


def render(args):
    try:
        path, time = snapshot(args.input, args.time)
    except RunFileError as error:
        sys.exit(f"render_sigma_ry: {error}")
    xy, arrays = read_point_arrays(path)
    if args.array not in arrays or arrays[args.array].ndim != 1:
        scalars = ", ".join(name for name, values in arrays.items() if values.ndim == 1)
        sys.exit(f"render_sigma_ry: {path} has no scalar point array {args.array}; it has: {scalars}")
    if (args.exclude_body or args.pile_body is not None) and "body" not in arrays:
        sys.exit(f"render_sigma_ry: {path} has no point array body to select bodies by")
    body = arrays.get("body", np.zeros(len(xy), dtype=int))
    values = arrays[args.array] / 1e3  # kPa
    pile = body == args.pile_body
    coloured = ~np.isin(body, args.exclude_body) & ~pile

    if args.window:
        r0, r1, y0, y1 = args.window
    else:
        # All particles, with a margin so that those on the edge are drawn whole.
        (r0, y0), (r1, y1) = xy.min(axis=0), xy.max(axis=0)
        margin = 0.02 * max(r1 - r0, y1 - y0, 1e-9)
        r0, r1, y0, y1 = r0 - margin, r1 + margin, y0 - margin, y1 + margin
    inside = coloured & (xy[:, 0] >= r0) & (xy[:, 0] <= r1) & (xy[:, 1] >= y0) & (xy[:, 1] <= y1)
    if not inside.any():
        sys.exit(f"render_sigma_ry: no particles of {path} to colour inside r {r0:g}..{r1:g} m, y {y0:g}..{y1:g} m")
    print(f"{args.array} in window: {values[inside].min():.6g} to {values[inside].max():.6g} kPa "
          f"({np.count_nonzero(inside)} particles)")
    finite = values[inside][np.isfinite(values[inside])]
    field = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)  # kPa
    if args.range:
        low, high = args.range
    else:
        bound = symmetric_bound(values[inside])
        low, high = -bound, bound
    print(f"colour range: {low:.6g} to {high:.6g} kPa")

    geometry = args.geometry or run_geometry(path)
    sides, geometry = domain_sides(xy, arrays, geometry)

    # The axes show the window at one scale in r and y, one image pixel per raster cell; the rest of
    # the image holds the axes' labels (left, bottom), the colour bar (right) and the title (top).
    if args.size:
        width, height = args.size
    else:
        width = 1000
        plot_height = (width - LEFT_PIXELS - BAR_PIXELS) * (y1 - y0) / (r1 - r0)
        height = int(min(2000, max(300, round(plot_height + TITLE_PIXELS + BOTTOM_PIXELS))))
    plot_width, plot_height = width - LEFT_PIXELS - BAR_PIXELS, height - TITLE_PIXELS - BOTTOM_PIXELS
    if plot_width < 50 or plot_height < 50:
        sys.exit(f"render_sigma_ry: an image of {width} x {height} pixels leaves no room for the field")
    pixels_per_metre = min(plot_width / (r1 - r0), plot_height / (y1 - y0))
    columns = max(1, int(round((r1 - r0) * pixels_per_metre)))
    rows = max(1, int(round((y1 - y0) * pixels_per_metre)))
    pixel = 1.0 / pixels_per_metre
    if not args.size:
        # A tall window capped at 2000 pixels high: the image narrows to the field, the bar beside it.
        width = LEFT_PIXELS + columns + BAR_PIXELS
        plot_width = columns
    left = LEFT_PIXELS + (plot_width - columns) // 2
    bottom = BOTTOM_PIXELS + (plot_height - rows) // 2

    # Particles whose domains reach into the window (their centres up to a domain outside it).
    near = ((xy[:, 0] + sides >= r0) & (xy[:, 0] - sides <= r1) & (xy[:, 1] + sides >= y0)
            & (xy[:, 1] - sides <= y1))
    soil = coloured & near
    if soil.any():
        what = geometry if geometry.startswith("no volume") else f"rectangles of the particles' areas, {geometry}"
        print(f"domains: {what}, "
              f"sides {np.min(sides[soil]):.4g} to {np.max(sides[soil]):.4g} m")
    raster = np.full((rows, columns), np.nan)
    kind = np.zeros((rows, columns), dtype=np.int8)  # 0 empty, 1 soil, 2 pile
    halves = np.zeros((2, len(xy)))
    halves[:, soil] = domain_halves(xy[soil], sides[soil])
    paint(raster, kind, xy[soil], halves[:, soil], values[soil], 1, r0, y0, pixel)
    drawn_pile = pile & near
    if drawn_pile.any():
        halves[:, drawn_pile] = domain_halves(xy[drawn_pile], sides[drawn_pile])
        paint(raster, kind, xy[drawn_pile], halves[:, drawn_pile], np.zeros(np.count_nonzero(drawn_pile)), 2,
              r0, y0, pixel)

    cmap, norm = diverging_map(low, high)
    rgb = cmap(norm(np.clip(np.nan_to_num(raster), low, high)))[..., :3]
    rgb[kind == 0] = BACKGROUND
    rgb[kind == 2] = (PILE_GREY, PILE_GREY, PILE_GREY)

    figure = plt.figure(figsize=(width / DPI, height / DPI), dpi=DPI, facecolor="white")
    axes = figure.add_axes((left / width, bottom / height, columns / width, rows / height))
    axes.imshow(rgb, origin="lower", extent=(r0, r0 + columns * pixel, y0, y0 + rows * pixel),
                interpolation="nearest", resample=False, aspect="equal")
    axes.set_xlim(r0, r0 + columns * pixel)
    axes.set_ylim(y0, y0 + rows * pixel)
    axes.set_xlabel("r [m]")
    axes.set_ylabel("y [m]")
    if drawn_pile.any():
        # The pile's outline (the edge of its particles' domains) and its tip's depth.
        axes.contour(np.arange(columns) * pixel + r0 + 0.5 * pixel, np.arange(rows) * pixel + y0 + 0.5 * pixel,
                     (kind == 2).astype(float), levels=[0.5], colors="black", linewidths=0.8)
        tip = float(np.min(xy[drawn_pile, 1] - halves[1, drawn_pile]))
        if y0 <= tip <= y1:
            axes.axhline(tip, color="black", linestyle="--", linewidth=0.8)
            axes.annotate(f"pile tip, y = {tip:.3f} m", (r1, tip), xytext=(-4, 4), textcoords="offset points",
                          ha="right", va="bottom", fontsize=10)
        print(f"pile tip at y = {tip:.6g} m")
    mappable = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    bar_axes = figure.add_axes(((left + columns + 25) / width, bottom / height, 22 / width, rows / height))
    extend = clipped_ends(field, low, high)
    colour_bar = figure.colorbar(mappable, cax=bar_axes, extend=extend)
    colour_bar.set_label(bar_label(args.array, field, low, high))
    when_text = f" at t = {time:g} s" if time is not None else f" in {os.path.basename(path)}"
    figure.suptitle(args.title or f"{args.array}{when_text}, r {r0:.3g} to {r1:.3g} m, y {y0:.3g} to {y1:.3g} m",
                    y=1.0 - 0.5 * TITLE_PIXELS / height, va="center", fontsize=13)

    picture = Picture(figure, axes, colour_bar, height, left, bottom, pixels_per_metre, r0, y0)
    picture.columns, picture.rows = columns, rows
    if soil.any():
        half_r, half_y = halves[0, soil], halves[1, soil]
        picture.soil_box = (max(r0, float(np.min(xy[soil, 0] - half_r))), min(r1, float(np.max(xy[soil, 0] + half_r))),
                            max(y0, float(np.min(xy[soil, 1] - half_y))), min(y1, float(np.max(xy[soil, 1] + half_y))))
    return picture


def coverage(image, picture):
    """Fraction of the image's pixels inside the soil's bounding box that are not background."""
    r0, r1, y0, y1 = picture.soil_box
    top, c0 = picture.pixel(r0, y1)
    bottom, c1 = picture.pixel(r1, y0)
    # Whole pixels strictly inside the box, so that antialiased axis lines on its edges stay out.
    box = image[top + 1:bottom, c0 + 1:c1, :3]
    background = np.all(box == np.round(np.array(BACKGROUND) * 255).astype(np.uint8), axis=-1)
    return 1.0 - float(np.mean(background)), box.shape[0] * box.shape[1]


def main(argv=None):
    args = parse_arguments(argv)
    picture = render(args)
    if os.path.dirname(args.out):
        os.makedirs(os.path.dirname(args.out), exist_ok=True)
    try:
        picture.figure.savefig(args.out, dpi=DPI)
    except OSError as error:
        sys.exit(f"render_sigma_ry: cannot write {args.out} ({error})")
    image = plt.imread(args.out)
    image = np.round(image * 255).astype(np.uint8) if image.dtype != np.uint8 else image
    for r, y in args.check_pixel:
        row, column = picture.pixel(r, y)
        left, top = picture.left, picture.height - picture.bottom - picture.rows
        if not (left <= column < left + picture.columns and top <= row < top + picture.rows):
            print(f"pixel at ({r:g}, {y:g}): outside the view")
            continue
        rgb = image[row, column]
        print(f"pixel at ({r:g}, {y:g}): {colour_name(rgb)} (RGB {rgb[0]} {rgb[1]} {rgb[2]})")
    if args.coverage:
        if picture.soil_box is None:
            print("soil coverage: no soil in the window")
        else:
            fraction, count = coverage(image, picture)
            print(f"soil coverage: {fraction:.4f} of {count} pixels in the soil's bounding box carry a colour")
    plt.close(picture.figure)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
