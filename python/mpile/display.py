"""What a picture of a stress field shows: which bodies are the rigid structure (kept off the colour
scale), and the colour range, symmetric about zero so that the colour tells the sign of the stress.

Shared by tools/render_sigma_ry.py and tools/paraview_open_run.py, and plain numpy, so that the
same decisions are made (and tested) with or without ParaView.
"""
import numpy as np

RIGID_SUFFIX = " (rigid)"  # a rigid body's material is named "<body> (rigid)" in the snapshots
DEFAULT_PERCENTILE = 99.0


def symmetric_bound(values, percentile=DEFAULT_PERCENTILE, fallback=1.0):
    """The `percentile`th percentile of |values|: the colour range is -bound..+bound.

    A percentile, not the maximum, because a few particles at the pile tip or on the free surface
    reach stresses far beyond the bulk and would wash out the rest of the field. `fallback` when
    there are no values or all are zero (a snapshot before any load).
    """
    values = np.asarray(values, dtype=float)
    values = values[np.isfinite(values)]
    bound = float(np.percentile(np.abs(values), percentile)) if values.size else 0.0
    return bound or fallback


def rigid_bodies(body_names, material_names):
    """Indices of the rigid bodies, known from their materials' names ("<body> (rigid)")."""
    rigid = {name[: -len(RIGID_SUFFIX)] for name in material_names if name.endswith(RIGID_SUFFIX)}
    return [index for index, name in enumerate(body_names) if name in rigid]


def pile_bodies(body_names, material_names, requested=None):
    """The body indices to hide as the pile: `requested` (names or indices, e.g. from --pile-body)
    if given, else every rigid body. Refuses a requested name the snapshot does not have."""
    if requested is None:
        return rigid_bodies(body_names, material_names)
    chosen = []
    for item in requested:
        item = str(item)
        if item.lstrip("-").isdigit():
            chosen.append(int(item))
        elif item in body_names:
            chosen.append(body_names.index(item))
        else:
            raise ValueError(f"no body named {item!r}; the bodies are: " + ", ".join(body_names or ["(no names)"]))
    return chosen


def soil(body, hidden):
    """Mask of the particles not in the hidden bodies (the soil, whose stresses set the range)."""
    return ~np.isin(np.asarray(body), list(hidden))


def colour_range(snapshots, array, hidden):
    """(-b, b) for a colour map symmetric about zero over an animation of `snapshots`: b is the
    largest over the snapshots of each one's percentile bound of the soil's |values|, so that one
    scale holds for every frame and the most loaded frame uses all of it. In the array's unit."""
    bounds = []
    for snapshot in snapshots:
        values = snapshot.arrays[array]
        if "body" in snapshot.arrays:
            values = values[soil(snapshot.arrays["body"], hidden)]
        bounds.append(symmetric_bound(values, fallback=0.0))
    bound = max(bounds, default=0.0) or 1.0
    return -bound, bound


def particle_spacing(positions):
    """Median distance (m) to the nearest other particle over an even sample of up to 200
    particles: the size at which points drawn one per particle tile the soil like a continuum."""
    positions = np.asarray(positions, dtype=float)
    if len(positions) < 2:
        return 0.0
    sample = positions[:: max(1, len(positions) // 200)]
    distances = [np.partition(np.hypot(*(positions - p).T), 1)[1] for p in sample]
    return float(np.median(distances))
