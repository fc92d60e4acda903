#!/usr/bin/python3
"""Render a stress field of one mpile particle snapshot to a PNG with VTK's own renderer (off-screen),
so that the picture is what ParaView shows: particles as points coloured with ParaView's "Cool to Warm"
diverging map, symmetric about zero, in kPa, seen on the r-y plane (r to the right, y up).

  tools/render_sigma_ry.py out/jacked/particles.pvd --out sigma_ry.png --time 2.0 --pile-body 3
  tools/render_sigma_ry.py out/jacked/particles_000004.vtu --out zoom.png --window 0 10 20 35 --range -50 50

Without a display, run it under xvfb-run: `xvfb-run -a /usr/bin/python3 tools/render_sigma_ry.py ...`.
The colour range defaults to +/- the 99th percentile of |value| inside the window; the rigid pile's
particles can be left out (--exclude-body) or drawn in grey (--pile-body) so they stay off the scale.
--check-pixel R Y prints the colour of the image at the physical point (r, y): red, light red, white,
light blue, blue, grey (pile) or other.

Reads snapshots and picks the colour range with the mpile package (python/mpile); uses Debian's
python3-vtk9 and python3-numpy (installed by tools/setup.sh).
"""
import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np
import vtkmodules.vtkRenderingFreeType  # noqa: F401  text of the scalar bar and title
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  the render window implementation
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersGeneral import vtkVertexGlyphFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from mpile.display import particle_spacing, symmetric_bound  # noqa: E402
from mpile.files import RunFileError  # noqa: E402
from mpile.snapshots import open_snapshots, read_vtu  # noqa: E402

BAR_PIXELS = 170  # band at the right of the image kept for the scalar bar
TITLE_PIXELS = 40  # band at the top of the image kept for the title
PILE_GREY = 0.5


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


def point_cloud(xy, z, scalars=None):
    """Vertices at (r, y, z), optionally with point scalars."""
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.column_stack([xy, np.full(len(xy), z)]), deep=True))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    if scalars is not None:
        cloud.GetPointData().SetScalars(numpy_to_vtk(scalars, deep=True))
    vertices = vtkVertexGlyphFilter()
    vertices.SetInputData(cloud)
    vertices.Update()
    return vertices.GetOutput()


def points_actor(cloud, size, lookup=None, colour_range=None):
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(cloud)
    if lookup is None:
        mapper.ScalarVisibilityOff()
    else:
        mapper.SetLookupTable(lookup)
        mapper.SetScalarRange(*colour_range)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetPointSize(size)
    if lookup is None:
        actor.GetProperty().SetColor(PILE_GREY, PILE_GREY, PILE_GREY)
    return actor


def cool_to_warm(low, high):
    """ParaView's default diverging map: blue at `low`, red at `high` and near-white at zero when the
    range spans it (so that the colour tells the sign even for an asymmetric --range), else midway."""
    lookup = vtkColorTransferFunction()
    lookup.SetColorSpaceToDiverging()
    lookup.AddRGBPoint(low, 0.231373, 0.298039, 0.752941)
    lookup.AddRGBPoint(0.0 if low < 0.0 < high else 0.5 * (low + high), 0.865, 0.865, 0.865)
    lookup.AddRGBPoint(high, 0.705882, 0.0156863, 0.14902)
    return lookup


def scalar_bar(lookup, title, viewport):
    """A renderer of its own holding the scalar bar, beside the data."""
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lookup)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%-#6.4g")
    bar.SetPosition(0.1, 0.03)
    bar.SetWidth(0.8)
    bar.SetHeight(0.82)
    bar.SetVerticalTitleSeparation(12)  # keeps the top label clear of the title
    bar.UnconstrainedFontSizeOn()
    for text, size in ((bar.GetTitleTextProperty(), 20), (bar.GetLabelTextProperty(), 18)):
        text.SetColor(0.0, 0.0, 0.0)
        text.SetFontFamilyToTimes()  # VTK's embedded Arial draws "[" and "]" as parentheses
        text.SetFontSize(size)
        text.ShadowOff()
        text.ItalicOff()
        text.BoldOff()
    renderer = vtkRenderer()
    renderer.SetViewport(*viewport)
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor2D(bar)
    return renderer


def title_bar(text, viewport):
    """A renderer of its own holding the title, above the data."""
    title = vtkTextActor()
    title.SetInput(text)
    title.GetTextProperty().SetColor(0.0, 0.0, 0.0)
    title.GetTextProperty().SetFontFamilyToTimes()
    title.GetTextProperty().SetFontSize(20)
    title.GetTextProperty().SetJustificationToCentered()
    title.GetTextProperty().SetVerticalJustificationToCentered()
    title.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    title.GetPositionCoordinate().SetValue(0.5, 0.5)
    renderer = vtkRenderer()
    renderer.SetViewport(*viewport)
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor2D(title)
    return renderer


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


def main():
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
    parser.add_argument("--pile-body", type=int, metavar="N", help="draw this body's particles in grey")
    parser.add_argument("--title", help="title text (default: the array, the time and the window)")
    parser.add_argument("--size", type=int, nargs=2, metavar=("W", "H"),
                        help="image size in pixels (default 1000 wide, height to fit the window)")
    parser.add_argument("--check-pixel", type=float, nargs=2, action="append", default=[], metavar=("R", "Y"),
                        help="print the colour of the image at the physical point (r, y); repeatable")
    args = parser.parse_args()
    if args.window and not (args.window[0] < args.window[1] and args.window[2] < args.window[3]):
        parser.error("--window needs R0 < R1 and Y0 < Y1")

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
    if args.range:
        low, high = args.range
    else:
        bound = symmetric_bound(values[inside])
        low, high = -bound, bound
    print(f"colour range: {low:.6g} to {high:.6g} kPa")

    # The data viewport shows the window at one scale in r and y; the rest of the image holds the
    # scalar bar (right) and the title (top).
    if args.size:
        width, height = args.size
    else:
        width = 1000
        data_height = (width - BAR_PIXELS) * (y1 - y0) / (r1 - r0)
        height = int(min(2000, max(300, round(data_height + TITLE_PIXELS))))
    top, right = 1 - TITLE_PIXELS / height, 1 - BAR_PIXELS / width
    data_width, data_height = width - BAR_PIXELS, height - TITLE_PIXELS
    pixels_per_metre = min(data_width / (r1 - r0), data_height / (y1 - y0))
    # Square points one particle spacing wide tile the soil like a continuum.
    point_size = max(1, math.ceil(particle_spacing(xy[coloured | pile]) * pixels_per_metre))

    lookup = cool_to_warm(low, high)
    scene = vtkRenderer()
    scene.SetViewport(0.0, 0.0, right, top)
    scene.SetBackground(1.0, 1.0, 1.0)
    scene.AddActor(points_actor(point_cloud(xy[coloured], 0.0, values[coloured]), point_size, lookup, (low, high)))
    if pile.any():
        # Slightly towards the camera, so that the pile is drawn over soil particles at the same place.
        scene.AddActor(points_actor(point_cloud(xy[pile], 1e-3 * (r1 - r0)), point_size))
    camera = scene.GetActiveCamera()
    camera.ParallelProjectionOn()
    centre_r, centre_y = 0.5 * (r0 + r1), 0.5 * (y0 + y1)
    camera.SetFocalPoint(centre_r, centre_y, 0.0)
    camera.SetPosition(centre_r, centre_y, 10.0 * max(r1 - r0, y1 - y0))
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetParallelScale(0.5 * data_height / pixels_per_metre)
    scene.ResetCameraClippingRange()

    when_text = f" at t = {time:g} s" if time is not None else f" in {os.path.basename(path)}"
    title = args.title or f"{args.array}{when_text}, r {r0:.3g} to {r1:.3g} m, y {y0:.3g} to {y1:.3g} m"

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(scene)
    window.AddRenderer(scalar_bar(lookup, f"{args.array} [kPa]", (right, 0.0, 1.0, top)))
    window.AddRenderer(title_bar(title, (0.0, top, 1.0, 1.0)))
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    image = grab.GetOutput()
    if os.path.dirname(args.out):
        os.makedirs(os.path.dirname(args.out), exist_ok=True)
    writer = vtkPNGWriter()
    writer.SetFileName(args.out)
    writer.SetInputData(image)
    writer.Write()
    if writer.GetErrorCode():
        sys.exit(f"render_sigma_ry: cannot write {args.out}")

    columns, rows, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(rows, columns, -1)  # row 0 at the bottom
    for r, y in args.check_pixel:
        # From the intended layout (window centred in the data viewport, one scale in r and y), not
        # from the camera, so that a wrong view shows up as a wrong colour.
        column = round(0.5 * data_width + (r - centre_r) * pixels_per_metre)
        row = round(0.5 * data_height + (y - centre_y) * pixels_per_metre)
        if not (0 <= column < data_width and 0 <= row < data_height):
            print(f"pixel at ({r:g}, {y:g}): outside the view")
            continue
        rgb = pixels[row, column]
        print(f"pixel at ({r:g}, {y:g}): {colour_name(rgb)} (RGB {rgb[0]} {rgb[1]} {rgb[2]})")
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
