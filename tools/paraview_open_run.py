#!/usr/bin/env pvpython
"""Open an mpile run in ParaView: the particle snapshots (particles.pvd) coloured by sigma_ry on
ParaView's "Cool to Warm" diverging map, symmetric about zero, with the range taken from the soil;
the pile (every rigid body, or --pile-body) hidden by a threshold on the point array `body`; the
view 2-D with r to the right and y up; the animation on the snapshot times, at the last one.

  pvpython tools/paraview_open_run.py out/jacked_quick
  pvpython tools/paraview_open_run.py out/gdp_quick --array sigma_yy --pile-body pile --screenshot s.png

In the ParaView GUI (View > Python Shell):

  import sys; sys.path.insert(0, "/path/to/mpile/tools")
  import paraview_open_run; paraview_open_run.open_run("/path/to/out/jacked_quick")

The decisions (which array, which bodies are the pile, the colour range, the times) are made by
plan(), which needs only numpy and VTK and is tested without ParaView (python/tests); open_run()
builds the ParaView pipeline from them. The colour range is +/- the largest over the snapshots of
each one's 99th percentile of |value| over the soil particles, so that one scale holds for the
whole animation and a few extreme particles at the pile tip do not wash out the field.
Needs ParaView 5.10 or later (the threshold's Invert).
"""
import argparse
import sys
from dataclasses import dataclass
from pathlib import Path

# The mpile package of this repository (python/mpile), so the script runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from mpile.display import colour_range, particle_spacing, pile_bodies, soil  # noqa: E402
from mpile.files import snapshots_path  # noqa: E402
from mpile.snapshots import open_snapshots  # noqa: E402

PRESET = "Cool to Warm"


@dataclass
class Plan:
    """What the ParaView view shows of one run."""

    pvd: Path
    array: str
    hidden: list  # body indices hidden by thresholds (the pile)
    hidden_names: list
    colour_range: tuple  # (low, high) in the array's unit (Pa for stresses), low = -high
    times: list  # s, the snapshot times the animation steps through
    soil_particles: int  # in the last snapshot, after the pile is hidden
    spacing: float  # m, median particle spacing in the last snapshot: the size of a drawn particle
    centre: tuple  # (r, y) of the middle of the soil in the last snapshot, where the camera looks


def plan(run, array="sigma_ry", pile_body=None):
    """The decisions for a run directory (or its particles.pvd), from the snapshots themselves.

    `pile_body`: names or indices of the bodies to hide; default every rigid body (a rigid body's
    material is named "<body> (rigid)" in the snapshots' field data).
    """
    pvd = snapshots_path(run)
    if pvd.suffix != ".pvd":
        raise ValueError(f"{pvd}: give a run directory or its particles.pvd, not a single snapshot")
    snapshots = open_snapshots(pvd)
    if not snapshots:
        raise ValueError(f"{pvd} lists no snapshots")
    last = snapshots[-1]
    scalars = last.scalars()
    if array not in scalars:
        raise ValueError(f"{last.path} has no scalar point array {array}; it has: {', '.join(scalars)}")
    hidden = pile_bodies(last.body_names, last.material_names, pile_body)
    if hidden and "body" not in last.arrays:
        raise ValueError(f"{last.path} has no point array body to hide the pile by")
    names = [last.body_names[i] if i < len(last.body_names) else f"body {i}" for i in hidden]
    kept = soil(last.arrays["body"], hidden) if "body" in last.arrays else slice(None)
    positions = last.positions[kept]
    centre = tuple(0.5 * (positions.min(axis=0) + positions.max(axis=0))) if len(positions) else (0.0, 0.0)
    return Plan(pvd=pvd, array=array, hidden=hidden, hidden_names=names,
                colour_range=colour_range(snapshots, array, hidden), times=list(snapshots.times),
                soil_particles=len(positions), spacing=particle_spacing(positions), centre=centre)


def describe(decided):
    """The plan as the lines the script prints."""
    low, high = decided.colour_range
    hidden = ", ".join(f"{name} ({index})" for name, index in zip(decided.hidden_names, decided.hidden))
    return [f"snapshots: {decided.pvd}",
            f"times: {', '.join(f'{t:g}' for t in decided.times)} s",
            f"colour: {decided.array} on {PRESET}, {low:.6g} to {high:.6g}",
            f"pile hidden: {hidden or 'none'}",
            f"soil particles in the last snapshot: {decided.soil_particles}"]


def hide_body(simple, source, index):
    """A threshold that drops the particles of body `index` (a vertex per particle)."""
    threshold = simple.Threshold(Input=source)
    threshold.Scalars = ["POINTS", "body"]
    if not hasattr(threshold, "Invert"):
        raise RuntimeError("this ParaView's Threshold has no Invert: ParaView 5.10 or later is needed")
    threshold.LowerThreshold = index - 0.5
    threshold.UpperThreshold = index + 0.5
    if hasattr(threshold, "ThresholdMethod"):
        threshold.ThresholdMethod = "Between"
    threshold.Invert = 1
    return threshold


def open_run(run, array="sigma_ry", pile_body=None, screenshot=None):
    """Builds the pipeline and the view in the running ParaView (pvpython or the GUI's shell) and
    returns the plan. With `screenshot`, also saves the view to that PNG."""
    try:
        from paraview import simple
    except ImportError:
        raise RuntimeError("ParaView's Python (paraview.simple) is not here: run this under pvpython or in "
                           "ParaView's Python shell (--plan-only prints the decisions without it)") from None
    decided = plan(run, array, pile_body)
    print("\n".join(describe(decided)))
    reader = simple.PVDReader(FileName=str(decided.pvd))
    source = reader
    for index in decided.hidden:
        source = hide_body(simple, source, index)
    simple.RenameSource(f"{decided.array} of the soil", source)

    view = simple.GetActiveViewOrCreate("RenderView")
    display = simple.Show(source, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Plain circle"
    # Discs a little wider than the particle spacing tile the soil like a continuum at any zoom.
    display.GaussianRadius = 0.6 * decided.spacing if decided.spacing > 0.0 else 0.01
    simple.ColorBy(display, ("POINTS", decided.array))
    lut = simple.GetColorTransferFunction(decided.array)
    lut.ApplyPreset(PRESET, True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(*decided.colour_range)
    simple.GetOpacityTransferFunction(decided.array).RescaleTransferFunction(*decided.colour_range)
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = f"{decided.array} [Pa]" if decided.array.startswith("sigma_") else decided.array
    bar.ComponentTitle = ""

    # 2-D: looking along -z at the r-y plane, r to the right and y up.
    view.InteractionMode = "2D"
    r, y = decided.centre
    view.CameraFocalPoint = [r, y, 0.0]
    view.CameraPosition = [r, y, 1.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.OrientationAxesVisibility = 0

    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = decided.times[-1]
    simple.SetActiveSource(source)
    view.ResetCamera(False)

    source.UpdatePipeline(decided.times[-1])
    shown = source.GetDataInformation().GetNumberOfPoints()
    steps = list(simple.GetTimeKeeper().TimestepValues or [])
    print(f"paraview: {len(steps)} time steps from {min(steps, default=0):g} to {max(steps, default=0):g} s; "
          f"{shown} particles shown at t = {decided.times[-1]:g} s; colour range "
          f"{lut.RGBPoints[0]:.6g} to {lut.RGBPoints[-4]:.6g}")
    if screenshot:
        simple.SaveScreenshot(str(screenshot), view, ImageResolution=[1200, 900])
        print(screenshot)
    else:
        simple.Render(view)
    return decided


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run", help="output directory of an mpile run, or its particles.pvd")
    parser.add_argument("--array", default="sigma_ry", help="point array to colour by (default sigma_ry)")
    parser.add_argument("--pile-body", action="append", metavar="NAME|INDEX",
                        help="body to hide as the pile (repeatable; default: every rigid body)")
    parser.add_argument("--screenshot", metavar="PNG", help="save the view to this PNG")
    parser.add_argument("--plan-only", action="store_true",
                        help="print the decisions and stop (no ParaView needed)")
    args = parser.parse_args(argv)
    try:
        if args.plan_only:
            print("\n".join(describe(plan(args.run, args.array, args.pile_body))))
        else:
            open_run(args.run, args.array, args.pile_body, args.screenshot)
    except (ValueError, KeyError, RuntimeError) as error:
        print(f"paraview_open_run: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
