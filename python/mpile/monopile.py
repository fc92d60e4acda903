"""The monopile installation of a run, as the seed paper's figures 3 to 7 show it: the forces of
the soil on the pile's tip, external and internal shaft against penetration, the friction ratios
on the shafts, and penetration against time since the start of the installation.

Only the rows of the case's last phase (the installation) are used; the pile is held still
before it. Penetration is the pile's total downward displacement (/bodies/<pile>/penetration, or
-u_y in files without it), the measure the case's stop_at and snapshot_penetrations use. Forces are
those of the soil on the pile per radian of circumference (r outward, y up, theta along the spin),
in kN/rad.
"""
from dataclasses import dataclass, field

import numpy as np

from .files import RunFileError, history_path
from .history import attributes, case as case_of, read_series
from .phase_table import phases

COMPONENTS = ("F_r", "F_y", "F_theta")
SURFACES = ("tip", "external_shaft", "internal_shaft")
# Penetrations are differences of recorded displacements: a row meant to be at 0.3 m may hold
# 0.29999999999999993 m, which still counts as reaching 0.3 m.
REACHED_TOLERANCE = 1e-9  # m
# Ratios are left out where |F_r| is below this fraction of its maximum over the installation.
RADIAL_CUTOFF = 1e-3


@dataclass
class Installation:
    """The installation phase of one run."""

    label: str
    time: np.ndarray  # s since the start of the installation
    penetration: np.ndarray  # m
    forces: dict = field(default_factory=dict)  # surface -> component -> kN/rad

    def index_at(self, penetration):
        """Index of the first row at or beyond `penetration` (m), or None if it was not reached:
        `run.time[i]`, `run.forces["tip"]["F_y"][i]` are that row's values."""
        reached = np.flatnonzero(self.penetration >= penetration - REACHED_TOLERANCE)
        return int(reached[0]) if reached.size else None

    def row_at(self, penetration):
        """The first row at or beyond `penetration` (m) as an `InstallationRow` (its index, time,
        penetration and forces, surface -> component -> kN/rad), or None if it was not reached."""
        index = self.index_at(penetration)
        if index is None:
            return None
        forces = {surface: {component: float(values[index]) for component, values in components.items()}
                  for surface, components in self.forces.items()}
        return InstallationRow(index, float(self.time[index]), float(self.penetration[index]), forces)


@dataclass(frozen=True)
class InstallationRow:
    """One row of an `Installation`: the values its arrays hold at `index`."""

    index: int
    time: float  # s since the start of the installation
    penetration: float  # m
    forces: dict  # surface -> component -> kN/rad


def blow_interval(case):
    """The interval (s) of a pulse-train drive (impact blows) in the case, or None."""
    for key in ("force_y", "velocity_y"):
        drive = case.get("monopile", {}).get("drive", {}).get(key)
        if isinstance(drive, dict) and drive.get("type") == "pulse_train":
            return float(drive["interval"])
    return None


def on_blow_clock(time, simulated, real):
    """Maps times of blows `simulated` s apart onto blows `real` s apart: blow k starts at k real.
    Valid when the pile and soil are at rest before each blow, so the wait adds nothing else."""
    blow = np.floor(time / simulated + 1e-9)
    return time + blow * (real - simulated)


def installation(path, body="pile", surfaces=SURFACES, real_blow_interval=None, label=None):
    """The installation phase of a run (its directory or history.h5) as an `Installation`.

    `label` defaults to the run's title. With `real_blow_interval`, an impact-driven run (pulse
    train drive) is drawn as if its blows were that many seconds apart (the seed's 0.85 s when the
    run struck more often).
    """
    path = history_path(path)
    attrs = attributes(path)
    names = ["/time", "/phase", f"/bodies/{body}/u_y"]
    names += [f"/reactions/{body}/{surface}/{component}" for surface in surfaces for component in COMPONENTS]
    series = read_series(path, names)
    with_penetration = f"/bodies/{body}/penetration"
    try:
        penetration = read_series(path, [with_penetration, "/time"])[with_penetration]
    except RunFileError:  # files written before /bodies/<body>/penetration
        penetration = -series[f"/bodies/{body}/u_y"]
    penetration = penetration[: len(series["/time"])]

    phase = series["/phase"]
    table = phases(path)
    # The case's phases (not the rows') say which is last, so that a run stopped before its
    # installation is not taken for one.
    last = len(table) - 1 if len(table) else int(phase.max(initial=0))
    rows = phase == last
    if not rows.any():
        raise RunFileError(f"{path} has no rows of its last phase (index {last:g}), the installation")
    start = table["start"].iloc[last] if len(table) else np.nan
    if not np.isfinite(start):
        before = np.flatnonzero(phase < last)
        start = series["/time"][before[-1]] if before.size else 0.0
    time = series["/time"][rows] - start
    interval = blow_interval(case_of(path))
    if real_blow_interval and interval:
        time = on_blow_clock(time, interval, real_blow_interval)
    forces = {surface: {component: series[f"/reactions/{body}/{surface}/{component}"][rows] / 1e3
                        for component in COMPONENTS} for surface in surfaces}
    return Installation(label or attrs.get("title", str(path)), time, penetration[rows], forces)


def ratio(numerator, radial):
    """numerator / radial, NaN where radial is below RADIAL_CUTOFF of its maximum (no division by ~0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(radial < RADIAL_CUTOFF * np.max(radial, initial=0.0), np.nan, numerator / radial)


def shaft_ratios(forces):
    """(|F_y| / |F_r|, sqrt(F_y^2 + F_theta^2) / |F_r|) of one surface's forces: the mobilised
    friction in the axial direction and in total, to set against the contact friction coefficient."""
    radial = np.abs(forces["F_r"])
    return ratio(np.abs(forces["F_y"]), radial), ratio(np.hypot(forces["F_y"], forces["F_theta"]), radial)


def running_mean(values, time, window):
    """Mean over `window` seconds centred on each row; shorter windows at the ends, not zero-padded."""
    n = max(1, int(round(window / np.median(np.diff(time))))) if len(time) > 1 else 1
    kernel = np.ones(n)
    return np.convolve(values, kernel, "same") / np.convolve(np.ones_like(values), kernel, "same")


def smoothed_ratios(forces, time, window):
    """shaft_ratios of the running means of |F_r|, |F_y|, |F_theta| over `window` s: the ratio of
    means, not the mean of the ratio, so that instants where F_r passes through zero do not dominate."""
    mean = {c: running_mean(np.abs(forces[c]), time, window) for c in COMPONENTS}
    return shaft_ratios(mean)
