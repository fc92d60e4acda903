"""What an installation sends into the ground: the energy radiated through absorbing faces per
metre of penetration, and the peak particle velocity (PPV) at the soil points a case follows.

Only the installation (the case's last phase) counts, as in `mpile.installation`. The radiated
energy is /energy/radiated (J/rad, cumulative) from the row before the installation to its last
row; a run without absorbing faces has none (NaN). The PPV of a monitor is the largest magnitude
of its particle's velocity (v_r, v_y and, in axisymmetric runs, v_theta) over the installation's
rows: a sampled peak, as a geophone's at the history interval.
"""
from dataclasses import dataclass, field

import numpy as np

from .files import RunFileError, history_path
from .history import attributes, list_datasets, read_series
from .phase_table import last_phase_rows


@dataclass
class Radiation:
    """The ground vibration of one run's installation."""

    label: str
    penetration: float  # m gained during the installation
    radiated: float  # J/rad during the installation (NaN: no absorbing face)
    ppv: dict = field(default_factory=dict)  # monitor -> peak particle velocity (m/s)

    @property
    def radiated_per_metre(self):
        """J/rad per m of penetration (NaN without penetration or absorbing faces)."""
        return self.radiated / self.penetration if self.penetration > 0 else np.nan


def radiation(path, body="pile", monitors=None, label=None):
    """The installation's radiated energy and the PPV at `monitors` (default: every monitor of the
    run) of a run (its directory or history.h5) as a `Radiation`."""
    path = history_path(path)
    attrs = attributes(path)
    present = {name for name, _, _ in list_datasets(path)}
    if monitors is None:
        monitors = sorted({name.split("/")[2] for name in present
                           if name.startswith("/monitors/") and name.endswith("/v_r")})
    names = ["/time", "/phase", f"/bodies/{body}/penetration"]
    radiated_series = "/energy/radiated" in present
    if radiated_series:
        names.append("/energy/radiated")
    for monitor in monitors:
        for component in ("v_r", "v_y", "v_theta"):
            if f"/monitors/{monitor}/{component}" in present:
                names.append(f"/monitors/{monitor}/{component}")
            elif component != "v_theta":
                raise RunFileError(f"{path} has no dataset /monitors/{monitor}/{component}")
    series = read_series(path, names)
    # The installation starts where the row before it ended.
    rows, before = last_phase_rows(path, series["/phase"], "the installation")
    penetration = series[f"/bodies/{body}/penetration"]
    gained = float(penetration[rows[-1]] - penetration[before])
    radiated = np.nan
    if radiated_series:
        energy = series["/energy/radiated"]
        radiated = float(energy[rows[-1]] - energy[before])
    ppv = {}
    for monitor in monitors:
        speed2 = np.zeros(rows.size)
        for component in ("v_r", "v_y", "v_theta"):
            name = f"/monitors/{monitor}/{component}"
            if name in series:
                speed2 += series[name][rows] ** 2
        ppv[monitor] = float(np.sqrt(np.nanmax(speed2)))
    return Radiation(label or attrs.get("title", str(path)), gained, radiated, ppv)
