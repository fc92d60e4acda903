"""A load test after an installation: the load-settlement curve of the case's last phase and the
capacity at a settlement of 10 % of the pile's diameter (the usual criterion).

The load is the downward force the pile's drive applied (-/bodies/<pile>/driving_F_y, kN/rad; for
a prescribed velocity, what it took), the settlement the pile's penetration since the phase
began. The diameter is the case's [monopile] diameter unless given.
"""
from dataclasses import dataclass

import numpy as np

from .files import history_path
from .history import attributes, case as case_of, read_series
from .phase_table import last_phase_rows, phases

CAPACITY_SETTLEMENT = 0.1  # of the diameter


@dataclass
class LoadTest:
    """The load test (last phase) of one run."""

    label: str
    settlement: np.ndarray  # m since the load test began
    load: np.ndarray  # kN/rad, downward
    diameter: float  # m (NaN when unknown)
    ended: str  # why the phase ended, as the run recorded it

    def load_at(self, settlement):
        """The load (kN/rad) at a settlement (m), interpolated; NaN if the test stopped short."""
        if not self.settlement.size or settlement > self.settlement.max():
            return np.nan
        # The first passage: a settlement that dips back (unloading) does not count twice.
        first = int(np.flatnonzero(self.settlement >= settlement)[0])
        if first == 0:
            return float(self.load[0])
        s0, s1 = self.settlement[first - 1], self.settlement[first]
        w = (settlement - s0) / (s1 - s0) if s1 > s0 else 1.0
        return float(self.load[first - 1] + w * (self.load[first] - self.load[first - 1]))

    @property
    def capacity(self):
        """The load at a settlement of 10 % of the diameter (kN/rad); NaN if not reached."""
        return self.load_at(CAPACITY_SETTLEMENT * self.diameter)


def load_test(path, body="pile", diameter=None, label=None):
    """The last phase of a run (its directory or history.h5) as a `LoadTest`."""
    path = history_path(path)
    attrs = attributes(path)
    series = read_series(path, ["/time", "/phase", f"/bodies/{body}/penetration",
                                f"/bodies/{body}/driving_F_y"])
    rows, before = last_phase_rows(path, series["/phase"], "the load test")
    depth = series[f"/bodies/{body}/penetration"]
    settlement = depth[rows] - depth[before]
    load = -series[f"/bodies/{body}/driving_F_y"][rows] / 1e3
    if diameter is None:
        diameter = float(case_of(path).get("monopile", {}).get("diameter", np.nan))
    table = phases(path)
    ended = str(table["ended"].iloc[-1]) if len(table) and table["ended"].iloc[-1] else ""
    return LoadTest(label or attrs.get("title", str(path)), settlement, load, diameter, ended)
