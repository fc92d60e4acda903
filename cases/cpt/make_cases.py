#!/usr/bin/env python3
"""Writes the CPT calibration-chamber cases cpt_r<N>.toml (N cells per cone radius).

The standard cone (ISO 22476-1: 35.7 mm, 60 degree apex, a 133.7 mm friction sleeve right above
it) jacked into the seed paper's Hardening Soil sand (Table 5) in a chamber at a uniform vertical
effective stress of 50 kPa (the seed's CPT, section 2.4) and K0 = 0.5. Gravity is off: the stress
comes from a surcharge on the surface and the K0 procedure, so sigma'_v0 is the same at every depth
the cone passes. The rod is wished in place with its tip 0.3 m below the surface and jacked 0.6 m
(17 diameters) at constant velocity.

cpt_coarse.toml is the suite's regression case (2 cells per radius, 0.15 m).

The grid is fine (R / N) in a band that moves with the cone, from 4 radii below the tip to 2 radii
above the sleeve, and in r out to 3 radii; it grows by 1.15 per cell to 50 mm away from them.
Lines above the band stretch up to the loaded surface, which stays put; above it there is only the
rod. Run `python3 cases/cpt/make_cases.py` to rewrite the files after changing this script.

Variants for docs/cpt.md: `make_cases.py OUT.toml N PENETRATION key=value ...` with the keywords of
case(). `geometry=plane_strain moving=false` makes the rod a plane-strain strip of the same
half-width (a rigid half strip held to its plane of symmetry) on a fixed grid, whose fine band
reaches the end of the penetration: the moving mesh follows axisymmetric bodies only.
"""
import math
import pathlib

RADIUS = 0.0357 / 2.0  # m, cone radius (10 cm^2 cone)
CONE_HEIGHT = RADIUS * math.sqrt(3.0)  # 60 degree apex: tan 30 deg = R / height
SLEEVE = 0.1337  # m, 150 cm^2 / (pi 35.7 mm)
CHAMBER_RADIUS = 0.6  # m, 34 cone radii
SURFACE = 2.2  # m, the loaded soil surface; the base is at y = 0
EMBEDMENT = 0.3  # m, initial depth of the cone tip
PENETRATION = 0.6  # m jacked
HEAD_ROOM = 0.7  # m of rod above the surface (more than the penetration)
COARSE = 0.05  # m, the largest cell
GROWTH = 1.15
SPEED = 0.5  # m/s, with mass scaling 100 (docs/cpt.md: the rate study)


def graded(start, end, near, largest, growth):
    """Cells from start towards end (either direction): `near`, growing by `growth` up to
    `largest`, scaled to land on end. Returns the cell sizes in the order they are laid."""
    length = abs(end - start)
    sizes = []
    h = near
    while sum(sizes) + h < length:
        sizes.append(h)
        h = min(h * growth, largest)
    # The remainder is spread over the cells laid, so no sliver cell is left.
    scale = length / sum(sizes) if sizes else 1.0
    return [s * scale for s in sizes] if sizes else [length]


def zones(nodes):
    """TOML zones of one cell each between consecutive nodes, merged where uniform."""
    out = []
    for a, b in zip(nodes[:-1], nodes[1:]):
        h = b - a
        if out and abs(out[-1][2] - h) < 1e-12 * max(1.0, h):
            out[-1][1] = b
            out[-1][3] += 1
        else:
            out.append([a, b, h, 1])
    return ",\n  ".join(
        f"{{ start = {a:.10g}, end = {b:.10g}, cells = {n} }}" for a, b, _, n in out
    )


def lay(nodes, sizes, end):
    """Appends nodes for cells of these sizes after nodes[-1], the last one exactly at end."""
    for size in sizes:
        nodes.append(nodes[-1] + size)
    nodes[-1] = end
    return nodes


def case(
    n,
    penetration=PENETRATION,
    flat=False,
    friction=0.4,
    speed=SPEED,
    mass_scaling=100.0,
    chamber_radius=CHAMBER_RADIUS,
    k0=0.5,
    bbar=True,
    particles_per_cell=2,
    normals="outline",
    sand=None,
    geometry="axisymmetric",
    moving=True,
    xpic_order=0,
):
    """The case text; the keywords vary it for docs/cpt.md's study. `sand` holds Hardening Soil
    keys set beside Table 5 (the model's own settings: ocr, stiffness_floor, cap_floor) or over it
    (dilatancy_angle, a sensitivity row only)."""
    sand = dict(sand or {})
    h = RADIUS / n
    tip = SURFACE - EMBEDMENT
    shoulder = tip + (0.0 if flat else CONE_HEIGHT)
    sleeve_top = shoulder + SLEEVE
    # On a fixed grid (`moving=false`; the moving mesh is axisymmetric only) the fine band reaches
    # down to 4 radii below where the tip ends.
    band_bottom = tip - 4.0 * RADIUS - (0.0 if moving else penetration)
    band_top = sleeve_top + 2.0 * RADIUS
    # Band lines on multiples of h from the tip, so that the tip is a grid line.
    below_cells = math.ceil((tip - band_bottom) / h - 1e-9)
    above_cells = math.ceil((band_top - tip) / h - 1e-9)
    band_bottom = tip - below_cells * h
    band_top = tip + above_cells * h
    top = SURFACE + max(HEAD_ROOM, penetration + 0.1)

    below = graded(band_bottom, 0.0, h, COARSE, GROWTH)
    y_nodes = lay([0.0], reversed(below), band_bottom)
    lay(y_nodes, [h] * (below_cells + above_cells), band_top)
    lay(y_nodes, graded(band_top, SURFACE, h, COARSE, GROWTH), SURFACE)
    lay(y_nodes, graded(SURFACE, top, 2.0 * h, COARSE, GROWTH), top)

    fine = 3 * n  # cells across the first 3 radii
    r_nodes = lay([0.0], [h] * fine, 3.0 * RADIUS)
    lay(r_nodes, graded(3.0 * RADIUS, chamber_radius, h, COARSE, GROWTH), chamber_radius)

    f = lambda x: f"{x:.10g}"  # noqa: E731
    # Flat-ended, the shoulder is at the tip and the edge named "cone" is the rod's base.
    rod = [(0.0, tip), (RADIUS, shoulder), (RADIUS, sleeve_top), (RADIUS, top), (0.0, top)]
    soil = [
        (0.0, 0.0),
        (chamber_radius, 0.0),
        (chamber_radius, SURFACE),
        (RADIUS, SURFACE),
        (RADIUS, shoulder),
        (0.0, tip),
    ]
    # Written only when varied, so that the shipped cases keep their defaults implicit.
    ppc_line = "" if particles_per_cell == 2 else f"particles_per_cell = {particles_per_cell}\n"
    bbar_line = "" if bbar else "bbar = false\n"
    xpic_line = f"xpic_order = {xpic_order}\n" if xpic_order else ""
    # Mass-gradient normals know no outline, so no named surfaces and no q_c: the rod's total force.
    outlined = normals == "outline"
    # In plane strain the "rod" is a strip of half-width RADIUS per metre, symmetric about r = 0
    # (a roller there), and q is its base's F_y over RADIUS: the engine's [output.cpt] is
    # axisymmetric only.
    plane = geometry == "plane_strain"
    surfaces_line = (
        'surfaces = ["cone", "sleeve", "shaft", "", ""]\n'
        if outlined
        else f'normals = "{normals}"\nsurface = "rod"\n'
    )
    cpt_output = (
        '\n[output.cpt]  # /cpt/q_c, f_s and R_f in history.h5\nbody = "cone"\ncone = "cone"\nsleeve = "sleeve"\n'
        if outlined and not plane
        else ""
    )
    moving_mesh = (
        f'[moving_mesh]\nbody = "cone"\nband = [{f(band_bottom)}, {f(band_top)}]\n'
        f"stretch = [0.0, {f(SURFACE)}]   # the loaded surface stays put\n"
        f"travel = {penetration + 0.02:.3g}\n"
        if moving
        else ""
    )
    symmetry_line = 'r_min = "roller"\n' if plane else ""
    # The half strip may neither slide off its plane of symmetry nor turn about its centre.
    held_line = (
        'velocity_r = { type = "constant", value = 0.0 }\n'
        'angular_velocity = { type = "constant", value = 0.0 }\n'
        if plane
        else ""
    )
    dilatancy = sand.pop("dilatancy_angle", 0.0)
    sand_lines = "".join(f"{k} = {v:g}\n" for k, v in sand.items())
    polygon = lambda pts: "[" + ", ".join(f"[{f(r)}, {f(y)}]" for r, y in pts) + "]"  # noqa: E731
    return f"""# CPT in a calibration chamber, {n} cells per cone radius. Written by cases/cpt/make_cases.py
# (its docstring gives the set-up); docs/cpt.md has the runs and what sets q_c.
title = "CPT, sigma'_v0 = 50 kPa, {n} cells per cone radius"
geometry = "{geometry}"

[grid]
r = [
  {zones(r_nodes)}
]
y = [
  {zones(y_nodes)}
]

[materials.sand]   # the seed's Table 5, as cases/monopile/jacked_quick.toml
type = "hardening_soil"
e50_ref = 44e6
eoed_ref = 44e6
eur_ref = 132e6
power = 0.47
poisson_ur = 0.2
k0_nc = 0.5
failure_ratio = 0.91
p_ref = 100e3
friction_angle = 37.5
dilatancy_angle = {float(dilatancy)}
density = 1656.25
{sand_lines}
[materials.steel]
type = "linear_elastic"
young_modulus = 210e9
poisson_ratio = 0.3
density = 7850.0

[[bodies]]
name = "chamber"
material = "sand"
region = {{ polygon = {polygon(soil)} }}
{ppc_line}
# The cone (60 degrees), its friction sleeve and the rod, as one rigid polygon from the tip.
[[bodies]]
name = "cone"
material = "steel"
region = {{ polygon = {polygon(rod)} }}

[bodies.rigid]
phase = "penetration"
velocity_y = {{ type = "ramp", value = {-speed}, duration = 0.01 }}
{held_line}
[[contact]]
structure = "cone"
friction = {friction}     # tan 21.8 deg, as the seed's pile
{surfaces_line}
{moving_mesh}
[boundaries]
r_max = "roller"
y_min = "roller"
{symmetry_line}
# The surcharge: sigma'_v0 = 50 kPa on the surface, beside the rod.
[[loads]]
name = "surcharge"
nodes = {{ y = {f(SURFACE)}, r = [{f(r_nodes[n + 1])}, {f(chamber_radius)}] }}
component = "y"
traction = -50e3

[solver]
gravity = [0.0, 0.0]
courant_number = 0.8
{bbar_line}{xpic_line}
[[phases]]
name = "chamber"
duration = 0.05
local_damping = 0.7
equilibrium_tolerance = 0.01
k0 = [{{ body = "chamber", surface = {f(SURFACE)}, surcharge = 50e3, k0 = {k0} }}]

[[phases]]
name = "penetration"
duration = {penetration / speed + 0.2:.3g}
stop_at = {{ body = "cone", penetration = {penetration} }}
mass_scaling = {mass_scaling}

[output]
history_interval = 0.002
snapshot_penetrations = {[d for d in (0.1, 0.3, 0.6) if d <= penetration]}
{cpt_output}"""


if __name__ == "__main__":
    import sys

    if len(sys.argv) > 1:  # a variant: make_cases.py OUT.toml N PENETRATION [key=value ...]
        options = dict(arg.split("=") for arg in sys.argv[4:])
        flags = ("flat", "bbar", "moving")
        sand = {k[len("sand."):]: float(v) for k, v in options.items() if k.startswith("sand.")}
        options = {
            k: (v == "true") if k in flags else int(v) if k in ("particles_per_cell", "xpic_order")
            else v if k in ("normals", "geometry") else float(v)
            for k, v in options.items() if not k.startswith("sand.")
        }
        options["sand"] = sand
        pathlib.Path(sys.argv[1]).write_text(case(int(sys.argv[2]), float(sys.argv[3]), **options))
        sys.exit(0)
    here = pathlib.Path(__file__).parent
    for n in (4, 6, 8):
        (here / f"cpt_r{n}.toml").write_text(case(n))
    # The suite's regression case: 2 cells per radius, jacked 0.15 m (tests/python_tools.cmake).
    (here / "cpt_coarse.toml").write_text(case(2, 0.15))
