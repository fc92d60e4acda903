"""history.h5 as an xarray Dataset or a pandas DataFrame: one row per history output.

Every series of the file is a 1-D dataset of one value per row. In the Dataset each becomes a
variable on the dimension `time`, named by its path in the file without the leading slash:

    /reactions/pile/tip/F_y   ->  ds["reactions/pile/tip/F_y"]
    /bodies/pile/u_y          ->  ds["bodies/pile/u_y"]
    /energy/kinetic           ->  ds["energy/kinetic"]

`time` (s), `step` and `phase` (index into the case's [[phases]]) are coordinates. Each variable
carries its `units`, and the attributes of its group (a contact surface's plan_area, side_area and
area_unit); the file's root attributes (title, status, case_text, ...) are the Dataset's.

The Dataset is built here from h5py, not from the file's dimension scales, so files written before
/time became one read the same.
"""
import numpy as np

from .files import RunFileError, history_path, plain, read_only, text, units_of

COORDINATES = ("time", "step", "phase")


def _series(history):
    """(path, dataset) of every 1-D numeric dataset in the file, in HDF5's (alphabetical) order."""
    import h5py

    found = []

    def visit(name, node):
        if isinstance(node, h5py.Dataset) and node.ndim == 1 and node.dtype.kind in "fiub":
            found.append(("/" + name, node))

    history.visititems(visit)
    return found


def _check_history(history, path):
    if "time" not in history or getattr(history["time"], "ndim", None) != 1:
        raise RunFileError(f"{path} is not an mpile history (it has no /time series)")


def list_datasets(path):
    """(path, units, number of values) of every dataset in the file, in the file's order."""
    import h5py

    path = history_path(path)
    with read_only(path) as history:
        rows = []
        history.visititems(lambda name, node: rows.append(("/" + name, units_of(node), node.shape[0]))
                           if isinstance(node, h5py.Dataset) and node.ndim >= 1 else None)
    return rows


def attributes(path):
    """The root attributes of the history (title, status, case_text, geometry, ...) as plain values."""
    path = history_path(path)
    with read_only(path) as history:
        _check_history(history, path)
        return {key: plain(value) for key, value in history.attrs.items()}


def read_series(path, names):
    """{name: array} of the named series ("/time", "/bodies/pile/u_y", ...), all of one length.

    Refuses a name the file does not have, naming the file and the series. A series read while
    the run writes may be a row longer than another (each is flushed in turn): all are cut to the
    shortest.
    """
    path = history_path(path)
    with read_only(path) as history:
        _check_history(history, path)
        for name in names:
            if name not in history:
                raise RunFileError(f"{path} has no dataset {name}")
        values = {name: history[name][:] for name in names}
    rows = min((len(v) for v in values.values()), default=0)
    return {name: v[:rows] for name, v in values.items()}


def _read(path):
    """Root attributes, and for every series its values, units and group attributes, of equal length."""
    path = history_path(path)
    with read_only(path) as history:
        _check_history(history, path)
        attrs = {key: plain(value) for key, value in history.attrs.items()}
        series = {}
        for name, node in _series(history):
            group = {key: plain(value) for key, value in node.parent.attrs.items()} if node.parent.name != "/" else {}
            series[name.lstrip("/")] = (node[:], units_of(node), group)
    lengths = {len(values) for values, _, _ in series.values()}
    rows = min(lengths)
    if len(lengths) > 1 and not attrs.get("status", "").startswith("running"):
        longest = max(series, key=lambda name: len(series[name][0]))
        shortest = min(series, key=lambda name: len(series[name][0]))
        raise RunFileError(f"{path}: the series differ in length ({shortest}: {len(series[shortest][0])} "
                           f"values, {longest}: {len(series[longest][0])}) though the run is "
                           f"{attrs.get('status', 'of unknown status')}")
    # A run still going may have flushed one series a row further than another: cut to the shortest.
    return attrs, {name: (values[:rows], units, group) for name, (values, units, group) in series.items()}


def open_history(path, form="xarray"):
    """The history of a run (its directory or its history.h5) as an xarray Dataset on `time`
    (form="xarray") or a pandas DataFrame indexed by time (form="pandas").

    The DataFrame has the same columns as the Dataset's variables plus `step` and `phase`; its
    `attrs` hold the file's root attributes and `attrs["units"]`, a dict of column -> units.
    The file is opened read-only without a lock and closed before this returns, so a run writing
    it is not disturbed; call again to see the rows written since.
    """
    if form not in ("xarray", "pandas"):
        raise ValueError(f"form must be 'xarray' or 'pandas', not {form!r}")
    attrs, series = _read(path)
    if form == "pandas":
        return _frame(attrs, series)
    return _dataset(attrs, series)


def _dataset(attrs, series):
    import xarray as xr

    time, time_units, _ = series["time"]
    coords = {"time": ("time", time, {"units": time_units or "s"})}
    for name in ("step", "phase"):
        if name in series:
            values, units, _ = series[name]
            # Files before /step and /phase were integers stored them as floats.
            coords[name] = ("time", values.astype(np.int64) if values.dtype.kind == "f" else values,
                            {"units": units})
    variables = {}
    for name, (values, units, group) in series.items():
        if name in COORDINATES:
            continue
        variables[name] = ("time", values, {**group, "units": units})
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def _frame(attrs, series):
    import pandas as pd

    time, time_units, _ = series["time"]
    columns, units = {}, {}
    for name, (values, unit, _) in series.items():
        if name == "time":
            continue
        columns[name] = values.astype(np.int64) if name in ("step", "phase") and values.dtype.kind == "f" else values
        units[name] = unit
    frame = pd.DataFrame(columns, index=pd.Index(time, name="time"))
    frame.attrs.update(attrs)
    frame.attrs["units"] = {"time": time_units or "s", **units}
    return frame


def case(path):
    """The case the run ran, parsed: a dict, {} if absent. The root attribute case_resolved holds
    it with its base files merged and --set values applied; older files have only the case file's
    own text (case_text), which was then the whole case."""
    import tomllib

    attrs = attributes(path)
    text_ = attrs.get("case_resolved") or attrs.get("case_text")
    return tomllib.loads(text(text_)) if text_ else {}
