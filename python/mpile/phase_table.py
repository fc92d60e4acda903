"""The phase table of a run: each phase's name, when it started and ended, and why it ended.

A run records it in history.h5 as /phases/<i> (attributes name, start, and once the phase has
ended, end and ended). Files written before that table existed only have the case file (root
attribute case_text) and the /phase series; there a phase starts at the last row of the phase
before it (or at 0), ends at its own last row once a later phase has begun or the run is
complete, and why it ended is not known.
"""
import tomllib

import numpy as np

from .files import RunFileError, history_path, plain, read_only, text

COLUMNS = ("name", "start", "end", "ended")


def phases(path):
    """The phases of the run's case as a pandas DataFrame indexed by phase (0, 1, ...), columns
    name, start (s), end (s) and ended (str). Phases not reached have start NaN; a phase still
    going (or cut off) has end NaN and ended None.

    Lists every phase of the case file, so that a run stopped before its last phase does not look
    like one that finished; the recorded /phases table wins where present.
    """
    import pandas as pd

    rows = _table(path)
    frame = pd.DataFrame([{key: row.get(key) for key in COLUMNS} for row in rows], columns=list(COLUMNS))
    frame["start"] = frame["start"].astype(float)
    frame["end"] = frame["end"].astype(float)
    frame.index.name = "phase"
    return frame


def last_phase_rows(path, phase, what):
    """The rows of the case's last phase in the /phase series `phase`, and the row before them (where
    the phase began; the first row when there is none). The case's phases, not the rows', say which
    is last, so that a run stopped before it is refused, naming `what` the phase is."""
    table = phases(path)
    last = len(table) - 1 if len(table) else int(phase.max(initial=0))
    rows = np.flatnonzero(phase == last)
    if not rows.size:
        raise RunFileError(f"{path} has no rows of its last phase (index {last:g}), {what}")
    return rows, (rows[0] - 1 if rows[0] > 0 else rows[0])


def _table(path):
    """One dict per phase: name, start, end, ended."""
    path = history_path(path)
    with read_only(path) as history:
        attrs = history.attrs
        source = attrs.get("case_resolved", attrs.get("case_text"))
        case = tomllib.loads(text(source)) if source is not None else {}
        status = text(attrs.get("status", ""))
        recorded = {}
        if "phases" in history:
            for key, group in history["phases"].items():
                if key.isdigit():
                    recorded[int(key)] = {k: plain(v) for k, v in group.attrs.items()}
        time = history["time"][:] if "time" in history else np.zeros(0)
        phase = history["phase"][:] if "phase" in history else np.zeros(0)
    rows = min(len(time), len(phase))
    time, phase = time[:rows], phase[:rows]

    listed = case.get("phases", [])
    count = max(len(listed), max(recorded, default=-1) + 1)
    table = []
    for index in range(count):
        entry = listed[index] if index < len(listed) else {}
        row = {"name": entry.get("name", f"phase {index}"), "start": np.nan, "end": np.nan, "ended": None}
        if index in recorded:
            row.update({key: recorded[index][key] for key in COLUMNS if key in recorded[index]})
        else:
            row.update(_from_rows(index, time, phase, count, status))
        table.append(row)
    return table


def _from_rows(index, time, phase, count, status):
    """start and end of phase `index` from the /phase series (files without /phases)."""
    own = np.flatnonzero(phase == index)
    if own.size == 0:
        return {}
    before = np.flatnonzero(phase < index)
    row = {"start": float(time[before[-1]]) if before.size else 0.0}
    later = np.any(phase > index)
    if later or (index == count - 1 and status.startswith("complete")):
        row["end"] = float(time[own[-1]])
    return row
