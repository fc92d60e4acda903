"""Friction fatigue: the radial effective stress beside a shaft against the number of load cycles.

    import mpile
    table = mpile.friction_fatigue("out/gdp_cycles_quick", frequency=60.0)
    table.loc[10]               # each monitor's sigma'_r / sigma'_r0 over the 10th cycle

A cycle's value is the mean over that cycle of the monitor's radial effective stress, divided by
the mean over the cycle before the first (the state the cycling starts from, read as the first
cycle's start value when no earlier row exists). Averaging over whole cycles removes the
oscillation within each cycle, so what is left is what the cycles have accumulated: contraction
(friction fatigue, sigma'_r falling) or dilation (rising).

The radial effective stress is compression positive, sigma'_r = -(sigma_rr - p_w), with p_w the
pore pressure (tension positive) where the monitor records one, so that dry and saturated runs
read alike.
"""
import numpy as np

from .files import RunFileError, history_path, read_only
from .phase_table import phases


def _monitor_names(path):
    with read_only(history_path(path)) as history:
        if "monitors" not in history:
            raise RunFileError(f"{history_path(path)} has no /monitors: the case follows no material point")
        return sorted(history["monitors"].keys())


def _radial_effective(history, name):
    group = history[f"monitors/{name}"]
    sigma_rr = group["sigma_rr"][:]
    pore = group["pore_pressure"][:] if "pore_pressure" in group else np.zeros_like(sigma_rr)
    return -(sigma_rr - pore)


def friction_fatigue(path, frequency, phase=None, monitors=None):
    """A pandas DataFrame indexed by cycle number N = 1, 2, ... (the cycles completed in the
    phase), one column per monitor: the mean of sigma'_r over cycle N over its mean over the cycle
    before the phase (or its value at the phase's start). `phase`: the cycling phase's name (the
    last phase by default); `monitors`: the names to read (all by default).

    Refuses a frequency that is not positive and a phase shorter than one cycle, naming the run.
    """
    import pandas as pd

    if not frequency > 0.0:
        raise ValueError(f"frequency must be positive (Hz), got {frequency}")
    table = phases(path)
    if phase is None:
        row = table.iloc[-1]
    else:
        matching = table[table["name"] == phase]
        if matching.empty:
            raise RunFileError(f"{history_path(path)}: no phase named {phase!r} "
                               f"(phases: {', '.join(table['name'])})")
        row = matching.iloc[0]
    start = float(row["start"])
    names = monitors or _monitor_names(path)
    with read_only(history_path(path)) as history:
        time = history["time"][:]
        stresses = {name: _radial_effective(history, name) for name in names}
    period = 1.0 / frequency
    end = time[-1] if np.isnan(row["end"]) else float(row["end"])
    cycles = int(np.floor((end - start) / period + 1e-9))
    if cycles < 1:
        raise RunFileError(f"{history_path(path)}: the phase from {start} s to {end} s holds no whole "
                           f"cycle of {period} s")
    # Each row's cycle, 1 for (start, start + period], ...: a row at a cycle's end, within a
    # millionth of a cycle of it (times are sums of steps), closes that cycle.
    cycle = np.ceil((time - start) / period - 1e-6).astype(np.int64)
    before = cycle == 0
    if before.any():
        before &= time >= start - period * (1.0 + 1e-6)
    first = np.argmin(np.abs(time - start))
    columns = {}
    for name, stress in stresses.items():
        reference = stress[before].mean() if before.any() else stress[first]
        values = []
        for n in range(1, cycles + 1):
            inside = cycle == n
            values.append(stress[inside].mean() / reference if inside.any() else np.nan)
        columns[name] = values
    return pd.DataFrame(columns, index=pd.Index(range(1, cycles + 1), name="cycle"))
