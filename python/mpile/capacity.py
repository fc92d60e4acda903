"""A load test after an installation: the load-settlement curve of the case's last phase and the
capacity at a settlement of 10 % of the pile's diameter (the usual criterion).

The load is the downward force the pile's drive applied (-/bodies/<pile>/driving_F_y, kN/rad; for
a prescribed velocity, what it took), the settlement the pile's penetration since the phase
began. The diameter is the case's [monopile] diameter unless given. Where the history has the
pile's surface reactions (/reactions/<pile>/<surface>/F_y), each surface's share is kept: the
soil's upward force on the tip and on each shaft, whose sum is the load plus the pile's weight.

`load_test_zone` measures the soil the test moved, from the particle snapshots at the test's start and
end: how far below the tip and out from the wall the sand moved by a given fraction of the
settlement, and how much of it the plug followed. `installation_reach` measures, the same way, the
sand the installation moved by a given distance: whether the test loads ground the installation
disturbed or ground it never reached.
"""
import gzip
from dataclasses import dataclass, field

import numpy as np

from .files import RunFileError, history_path
from .history import attributes, case as case_of, list_datasets, read_series
from .phase_table import last_phase_rows, phases
from .snapshots import rigid_particles

CAPACITY_SETTLEMENT = 0.1  # of the diameter


@dataclass
class LoadTest:
    """The load test (last phase) of one run."""

    label: str
    settlement: np.ndarray  # m since the load test began
    load: np.ndarray  # kN/rad, downward
    diameter: float  # m (NaN when unknown)
    ended: str  # why the phase ended, as the run recorded it
    surfaces: dict = field(default_factory=dict)  # {surface: upward F_y on it, kN/rad}

    def _at(self, values, settlement):
        # Not finite: a case without a diameter asked for its capacity.
        if not self.settlement.size or not np.isfinite(settlement) or settlement > self.settlement.max():
            return np.nan
        # The first passage: a settlement that dips back (unloading) does not count twice.
        first = int(np.flatnonzero(self.settlement >= settlement)[0])
        if first == 0:
            return float(values[0])
        s0, s1 = self.settlement[first - 1], self.settlement[first]
        w = (settlement - s0) / (s1 - s0) if s1 > s0 else 1.0
        return float(values[first - 1] + w * (values[first] - values[first - 1]))

    def load_at(self, settlement):
        """The load (kN/rad) at a settlement (m), interpolated; NaN if the test stopped short."""
        return self._at(self.load, settlement)

    def surface_at(self, surface, settlement):
        """The soil's upward force on one surface of the pile (kN/rad) at a settlement (m)."""
        return self._at(self.surfaces[surface], settlement)

    @property
    def shares(self):
        """{surface: its force at a settlement of 10 % of the diameter (kN/rad)}."""
        return {name: self.surface_at(name, CAPACITY_SETTLEMENT * self.diameter) for name in self.surfaces}

    @property
    def capacity(self):
        """The load at a settlement of 10 % of the diameter (kN/rad); NaN if not reached."""
        return self.load_at(CAPACITY_SETTLEMENT * self.diameter)


def _open_text(path, mode):
    """A text file, gzip-compressed where its name ends in .gz."""
    if str(path).endswith(".gz"):
        return gzip.open(path, mode + "t", encoding="utf-8")
    return open(path, mode, encoding="utf-8")


def write_load_test_csv(test, path, source=""):
    """Writes a `LoadTest` as CSV (gzip-compressed where `path` ends in .gz): a header of `# key:
    value` lines (label, diameter, how the test ended, `source`: the run's case and commit), then
    settlement (m), load and each surface's upward F_y (kN/rad) at every row, to six significant
    digits (0.1 um of a 0.1 m settlement, 0.1 N/rad of a 100 kN/rad load). The curves of runs that
    take hours are kept this way beside the page that shows them, so that a figure can be drawn
    again without the runs (about 100 kB a run compressed)."""
    names = sorted(test.surfaces)
    columns = [test.settlement, test.load] + [test.surfaces[n] for n in names]
    with _open_text(path, "w") as f:
        for key, value in (("label", test.label), ("diameter_m", repr(test.diameter)),
                           ("ended", test.ended), ("source", source)):
            f.write(f"# {key}: {' '.join(str(value).split())}\n")
        f.write(",".join(["settlement_m", "load_kN_per_rad"] + [f"{n}_kN_per_rad" for n in names]) + "\n")
        for row in zip(*columns):
            f.write(",".join(f"{float(v):.6g}" for v in row) + "\n")


def read_load_test_csv(path, label=None):
    """A `LoadTest` from a CSV that `write_load_test_csv` wrote; RunFileError names what is wrong."""
    header, rows, columns = {}, [], None
    try:
        with _open_text(path, "r") as f:
            for number, line in enumerate(f, 1):
                line = line.rstrip("\n")
                if line.startswith("# "):
                    key, _, value = line[2:].partition(": ")
                    header[key] = value
                elif columns is None:
                    columns = line.split(",")
                elif line:
                    values = [float(v) for v in line.split(",")]
                    if len(values) != len(columns):
                        raise RunFileError(f"{path}:{number}: {len(values)} values for {len(columns)} columns")
                    rows.append(values)
    except (OSError, EOFError, UnicodeDecodeError, ValueError) as e:
        raise RunFileError(f"{path}: not a load-test curve: {e}") from e
    if columns is None or columns[:2] != ["settlement_m", "load_kN_per_rad"]:
        raise RunFileError(f"{path}: not a load-test curve (its columns are not settlement_m, load_kN_per_rad, ...)")
    data = np.array(rows, dtype=float).reshape(len(rows), len(columns))
    surfaces = {name[:-len("_kN_per_rad")]: data[:, k] for k, name in enumerate(columns) if k >= 2}
    return LoadTest(label or header.get("label", str(path)), data[:, 0], data[:, 1],
                    float(header.get("diameter_m", "nan")), header.get("ended", ""), surfaces)


def load_test(path, body="pile", diameter=None, label=None):
    """The last phase of a run (its directory or history.h5) as a `LoadTest`; a `.csv` or `.csv.gz`
    path is a curve `write_load_test_csv` kept."""
    if str(path).endswith((".csv", ".csv.gz")):
        test = read_load_test_csv(path, label)
        if diameter is not None:
            test.diameter = diameter
        return test
    path = history_path(path)
    attrs = attributes(path)
    prefix = f"/reactions/{body}/"
    reactions = [name for name, _, _ in list_datasets(path) if name.startswith(prefix) and name.endswith("/F_y")]
    series = read_series(path, ["/time", "/phase", f"/bodies/{body}/penetration",
                                f"/bodies/{body}/driving_F_y", *reactions])
    rows, before = last_phase_rows(path, series["/phase"], "the load test")
    depth = series[f"/bodies/{body}/penetration"]
    settlement = depth[rows] - depth[before]
    load = -series[f"/bodies/{body}/driving_F_y"][rows] / 1e3
    surfaces = {name[len(prefix):-len("/F_y")]: series[name][rows] / 1e3 for name in reactions}
    if diameter is None:
        diameter = float(case_of(path).get("monopile", {}).get("diameter", np.nan))
    table = phases(path)
    ended = str(table["ended"].iloc[-1]) if len(table) and table["ended"].iloc[-1] else ""
    return LoadTest(label or attrs.get("title", str(path)), settlement, load, diameter, ended, surfaces)


@dataclass
class LoadTestZone:
    """The soil a load test moved by at least `fraction` of its settlement (distances in m; the
    tip's height and the wall's radii are the case's pile at the test's start)."""

    fraction: float
    below_tip: float  # how deep below the tip the moved sand reaches
    outside_wall: float  # how far out from the outer wall it reaches
    above_tip_outside: float  # how high above the tip it reaches outside the wall
    plug_follows: float  # the plug's mean settlement over the pile's (1: it goes down with the pile)


def load_test_zone(path, fraction=0.1, body="pile"):
    """The `LoadTestZone` of the run's load test (its last phase), from the particle snapshots at the
    phase's start and at its end (a run writes one at every phase end). Particles are followed by
    id; rigid bodies' particles are left out."""
    history = history_path(path)
    table = phases(history)
    start, end = float(table["start"].iloc[-1]), float(table["end"].iloc[-1])
    if not np.isfinite(end):
        raise RunFileError(f"{history} has no finished load test (its last phase has not ended)")
    first, last = _snapshots_at(history, start, end, "load test")
    monopile = case_of(history).get("monopile", {})
    outer = 0.5 * float(monopile.get("diameter", np.nan))
    return moved_zone(first, last, fraction, outer, outer - float(monopile.get("wall_thickness", np.nan)))


def _snapshots_at(history, start, end, what):
    """The particle snapshots at a phase's start and end (a run writes one at every phase end)."""
    from .snapshots import open_snapshots

    snapshots = open_snapshots(history.parent)
    first, last = snapshots.at(start), snapshots.at(end)
    if not (abs(first.time - start) <= 1e-9 * max(1.0, end) and abs(last.time - end) <= 1e-9 * max(1.0, end)):
        raise RunFileError(f"{history.parent} has no particle snapshots at the {what}'s start ({start:g} s) "
                           f"and end ({end:g} s)")
    return first, last


def _matched(first, last):
    """The two snapshots' particles matched by id (indices into each) and which are rigid."""
    ids_first, ids_last = first.arrays["id"].astype(np.int64), last.arrays["id"].astype(np.int64)
    _, a, b = np.intersect1d(ids_first, ids_last, return_indices=True)
    return a, b, rigid_particles(first)[a]


def moved_zone(first, last, fraction, outer, inner):
    """The `LoadTestZone` between two snapshots (objects with positions, arrays id and material, and
    material_names) of a pile whose wall spans radii inner to outer: the pile's settlement is its
    particles' mean downward movement, its tip their lowest point at the start."""
    a, b, is_rigid = _matched(first, last)
    r, y = first.positions[a, 0], first.positions[a, 1]
    moved = last.positions[b] - first.positions[a]
    tip = y[is_rigid].min()
    settlement = float(np.mean(-moved[is_rigid, 1]))
    soil = ~is_rigid
    zone = soil & (np.hypot(moved[:, 0], moved[:, 1]) >= fraction * settlement)
    outside = zone & (r > outer)
    plug = soil & (r < inner) & (y > tip)

    def largest(values):
        return float(values.max()) if values.size else 0.0

    return LoadTestZone(fraction, largest(tip - y[zone]), largest(r[outside] - outer), largest(y[outside] - tip),
                        float(np.mean(-moved[plug, 1]) / settlement) if plug.any() else np.nan)


@dataclass
class InstallationReach:
    """The sand an installation moved by at least `distance` (m), where it lies at the
    installation's end: how deep below the tip then and how far out from the outer wall."""

    distance: float
    below_tip: float
    outside_wall: float


def installation_reach(path, distance, phase="installation"):
    """The `InstallationReach` of the run's phase named `phase`, from the particle snapshots at its
    start and end."""
    history = history_path(path)
    table = phases(history)
    named = table[table["name"] == phase]
    if named.empty or not np.isfinite(float(named["end"].iloc[0])):
        raise RunFileError(f"{history} has no finished phase named '{phase}'")
    first, last = _snapshots_at(history, float(named["start"].iloc[0]), float(named["end"].iloc[0]), phase)
    outer = 0.5 * float(case_of(history).get("monopile", {}).get("diameter", np.nan))
    return moved_reach(first, last, distance, outer)


def moved_reach(first, last, distance, outer):
    """The `InstallationReach` between two snapshots (as `moved_zone` reads them) of a pile whose
    outer wall is at radius `outer`: soil particles that moved by at least `distance`, at their
    positions in the second snapshot, against the pile's lowest particle there (its tip)."""
    a, b, is_rigid = _matched(first, last)
    now = last.positions[b]
    moved = np.hypot(*(now - first.positions[a]).T)
    tip = now[is_rigid, 1].min()
    zone = ~is_rigid & (moved >= distance)
    below, out = tip - now[zone, 1], now[zone, 0] - outer
    return InstallationReach(distance, float(below.max()) if below.size else 0.0,
                             float(out[out > 0].max()) if (out > 0).any() else 0.0)


@dataclass
class RunRecord:
    """What a capacity run cost and how well its ledger closed: where and when its installation
    ended, how long its rest held the pile, its steps and wall time, and the energy residual (over
    the energy in play, as the run books it) at the installation's end and at the run's end."""

    depth: float  # m, the pile's penetration at the installation's end
    installed_at: float  # s
    rest: float  # s the phase named rest lasted (NaN without one)
    steps: int
    wall_time: float  # s, across continuations, at the last row
    ledger_installed: float  # relative residual at the installation's last row
    ledger_end: float  # at the last row (a finished run's last step)


def run_record(path, body="pile", phase="installation"):
    """The `RunRecord` of a run whose phase named `phase` has ended."""
    history = history_path(path)
    table = phases(history)
    named = table[table["name"] == phase]
    if named.empty or not np.isfinite(float(named["end"].iloc[0])):
        raise RunFileError(f"{history} has no finished phase named '{phase}'")
    index = int(named.index[0])
    # The last row's, not the file's attributes: a run still going (or stopped and to be continued)
    # wrote those at its last stop.
    series = read_series(history, ["/phase", "/step", "/wall_time", f"/bodies/{body}/penetration",
                                   "/energy/relative_residual"])
    rows = np.flatnonzero(series["/phase"] == index)
    if not rows.size:
        raise RunFileError(f"{history} has no rows of its phase '{phase}'")
    last = int(rows[-1])
    rest = table[table["name"] == "rest"]
    return RunRecord(depth=float(series[f"/bodies/{body}/penetration"][last]),
                     installed_at=float(named["end"].iloc[0]),
                     rest=float(rest["end"].iloc[0] - rest["start"].iloc[0]) if not rest.empty else np.nan,
                     steps=int(series["/step"][-1]), wall_time=float(series["/wall_time"][-1]),
                     ledger_installed=float(series["/energy/relative_residual"][last]),
                     ledger_end=float(series["/energy/relative_residual"][-1]))


@dataclass
class WallTipFill:
    """How many times over the soil particles fill three zones at the wall's tip, each a wall
    thickness deep below it: under the wall, beside it inside and beside it outside (each a wall
    thickness wide). Particles whose volumes and positions agree fill a zone about once; crowded
    ones, whose positions and volumes no longer agree, more."""

    time: float
    under: float
    inside: float
    outside: float


def wall_tip_fill(snapshot, outer, inner):
    """The `WallTipFill` of one snapshot (positions; arrays material, volume; material_names) of an
    axisymmetric pile whose wall spans radii inner to outer. Volumes are per radian, as
    axisymmetric runs write them: a square particle of side s at radius r has r s^2. The tip is
    the lowest rigid particle's lower edge, half its side below its centre (the centre alone put
    the zone half a side into the wall, where no soil is: 0.83 before any driving)."""
    is_rigid = rigid_particles(snapshot)
    rigid = np.flatnonzero(is_rigid)
    lowest = rigid[np.argmin(snapshot.positions[rigid, 1])]
    r_low, y_low = snapshot.positions[lowest]
    tip = float(y_low - 0.5 * np.sqrt(snapshot.arrays["volume"][lowest] / r_low))
    r, y = snapshot.positions[~is_rigid, 0], snapshot.positions[~is_rigid, 1]
    volume = snapshot.arrays["volume"][~is_rigid]
    t = outer - inner
    below = (y < tip) & (y > tip - t)

    def fill(r1, r2):
        return float(volume[below & (r > r1) & (r < r2)].sum() / (0.5 * (r2**2 - r1**2) * t))
    return WallTipFill(snapshot.time, fill(inner, outer), fill(max(inner - t, 0.0), inner), fill(outer, outer + t))


def wall_tip_fills(path):
    """The `WallTipFill` of every particle snapshot of a run of a [monopile] case."""
    from .snapshots import open_snapshots

    history = history_path(path)
    monopile = case_of(history).get("monopile", {})
    outer = 0.5 * float(monopile.get("diameter", np.nan))
    inner = outer - float(monopile.get("wall_thickness", np.nan))
    if not (0.0 < inner < outer):
        raise RunFileError(f"{history}: its case has no [monopile] diameter and wall_thickness")
    return [wall_tip_fill(snapshot, outer, inner) for snapshot in open_snapshots(history.parent)]
