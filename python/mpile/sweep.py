"""A parameter study run by `mpile sweep`: its table of results, one row per variant.

`mpile sweep study.toml` writes `sweep.toml` (the expanded sweep) and a Snakefile into its output
directory and runs every variant there (variants/<id>/). The workflow's last job calls `gather`,
which writes

    results.csv   one row per variant: id, the parameters' values, status, the gathered quantities
    results.nc    the same as an xarray Dataset on one dimension per parameter (netCDF)
    results.png   each gathered quantity against the parameter with the most values

A quantity the sweep file gathers is read from the variant's history.h5: `series` (a path in the
file) where a body first reaches `at_penetration` (interpolated between rows), at `at_time`, or
reduced over the run or one phase (last, max, min, mean, max_abs). It is NaN where the run did not
get there; `status` says whether the variant finished. A series no variant's history holds is a
misspelt path and fails the gathering, naming the nearest paths.

    import mpile
    table = mpile.open_sweep("out/sweeps/gdp_torque")            # xarray Dataset
    frame = mpile.open_sweep("out/sweeps/gdp_torque", form="pandas")
"""
import difflib
import math
import os
import tomllib
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .files import RunFileError, plain, read_only, units_of


def read_sweep(directory):
    """The expanded sweep (sweep.toml of the output directory) as a dict."""
    path = Path(directory) / "sweep.toml"
    if not path.is_file():
        raise RunFileError(f"{directory} holds no sweep.toml (is it the output of mpile sweep?)")
    with open(path, "rb") as f:
        return tomllib.load(f)


def _value(text):
    """A parameter value from its TOML text; an array or table stays text (an index needs values
    that hash)."""
    value = tomllib.loads("x = " + text)["x"]
    return text if isinstance(value, (list, dict)) else value


def _status(run):
    if (run / "finished").exists():
        return "finished"
    if not (run / "history.h5").exists():
        # output.log is what the attempt printed (run.log in sweeps written before it existed).
        tried = (run / "output.log").exists() or (run / "run.log").exists()
        return "failed" if tried else "not run"
    try:
        with read_only(run / "history.h5") as history:
            status = str(plain(history.attrs.get("status", "unknown")))
            return status if status.startswith(("failed", "interrupted")) else "failed: " + status
    except OSError:
        return "failed"


def quantity(history, spec):
    """(value, units) of one gathered quantity from an open history.h5."""
    series = spec["series"].lstrip("/")
    if series not in history:
        return math.nan, ""
    values = history[series][:].astype(float)
    units = units_of(history[series])
    time = history["time"][:]
    rows = min(len(values), len(time))
    values, time = values[:rows], time[:rows]
    if rows == 0:
        return math.nan, units
    if "at_penetration" in spec:
        name = f"bodies/{spec['body']}/penetration"
        if name not in history:
            return math.nan, units
        depth = history[name][:rows]
        target = spec["at_penetration"]
        reached = np.flatnonzero(depth >= target)
        if reached.size == 0:
            return math.nan, units
        i = reached[0]
        if i == 0 or depth[i] == depth[i - 1]:
            return float(values[i]), units
        s = (target - depth[i - 1]) / (depth[i] - depth[i - 1])
        return float(values[i - 1] + s * (values[i] - values[i - 1])), units
    if "at_time" in spec:
        t = spec["at_time"]
        if t < time[0] or t > time[-1]:
            return math.nan, units
        return float(np.interp(t, time, values)), units
    if "phase" in spec:
        names = {}
        if "phases" in history:
            for key, group in history["phases"].items():
                if key.isdigit():
                    names[str(plain(group.attrs.get("name", "")))] = int(key)
        if spec["phase"] not in names or "phase" not in history:
            return math.nan, units
        values = values[history["phase"][:rows] == names[spec["phase"]]]
        if values.size == 0:
            return math.nan, units
    reduce = {"last": lambda v: v[-1], "max": np.nanmax, "min": np.nanmin, "mean": np.nanmean,
              "max_abs": lambda v: np.nanmax(np.abs(v))}[spec["reduce"]]
    return float(reduce(values)), units


def check_gather_names(sweep, path):
    """Raises RunFileError naming the first [[gather]] entry of the sweep file at `path` whose name
    cannot be a column of the table (`name_problem`), before anything is read or written."""
    taken = {"variant", "status", *sweep.get("parameters", [])}
    for number, spec in enumerate(sweep.get("gather", []), start=1):
        name = spec.get("name")
        problem = name_problem(name, taken)
        if problem:
            raise RunFileError(f"{path}: [[gather]] number {number} (name = {name!r}): the name {problem}")
        taken.add(name)


def name_problem(name, taken):
    """Why `name` cannot be a gathered quantity's column in results.csv and variable in results.nc
    (the names in `taken` are columns already), or "" when it can.

    results.nc is netCDF-4 in HDF5: there '/' separates groups (h5netcdf fails on it with a bare
    KeyError) and "." is the group itself, and netCDF's rule for names wants a first character
    that is a letter, a digit, '_' or not ASCII, and no control characters. results.csv's columns
    hold no spaces, commas or double quotes, as the sweep file's reader requires. A name equal to
    variant, status, a parameter or another quantity would silently overwrite that column.
    """
    if not isinstance(name, str) or not name:
        return "is missing or empty"
    if "/" in name:
        return "contains '/', which results.nc (HDF5) would read as a path through groups"
    bad = next((c for c in name if c.isspace() or not c.isprintable() or c in ',"'), None)
    if bad is not None:
        return f"contains {bad!r}: a column name holds no spaces, commas, double quotes or control characters"
    if name[0].isascii() and not (name[0].isalnum() or name[0] == "_"):
        return f"starts with {name[0]!r}: a netCDF variable name starts with a letter, a digit or '_'"
    if name in taken:
        return "is a column already (variant, status, a parameter or another gathered quantity)"
    return ""


def table(directory):
    """The results as a pandas DataFrame (one row per variant) and the quantities' units."""
    import pandas as pd

    directory = Path(directory)
    sweep = read_sweep(directory)
    check_gather_names(sweep, directory / "sweep.toml")
    rows, units = [], {}
    # A series found in no readable history is a misspelt path, not an unreached value: said so
    # with the nearest names, where a column of NaN would pass for a result.
    found = {spec["name"]: False for spec in sweep.get("gather", [])}
    names = set()
    for variant in sweep["variants"]:
        run = directory / "variants" / variant["id"]
        row = {"variant": variant["id"]}
        row.update({key: _value(text) for key, text in zip(sweep["parameters"], variant["values"])})
        row["status"] = _status(run)
        history_file = run / "history.h5"
        for spec in sweep.get("gather", []):
            row[spec["name"]] = math.nan
        if history_file.exists():
            try:
                with read_only(history_file) as history:
                    history.visit(names.add)
                    for spec in sweep.get("gather", []):
                        found[spec["name"]] |= spec["series"].lstrip("/") in history
                        row[spec["name"]], unit = quantity(history, spec)
                        if unit:
                            units[spec["name"]] = unit
            except OSError:
                pass  # a history the failed run left unreadable: its quantities stay NaN
        rows.append(row)
    for number, spec in enumerate(sweep.get("gather", []), start=1):
        if names and not found[spec["name"]]:
            near = difflib.get_close_matches(spec["series"].lstrip("/"), sorted(names), n=3)
            raise RunFileError(f"{directory / 'sweep.toml'}: [[gather]] number {number} (name = "
                               f"{spec['name']!r}): series {spec['series']!r} is in no variant's "
                               f"history.h5" + (f"; nearest: {', '.join(near)}" if near else ""))
    return pd.DataFrame(rows), units


def to_xarray(frame, sweep, units):
    """The table as a Dataset on one dimension per parameter (a full product of their values)."""
    dataset = frame.set_index(list(sweep["parameters"])).to_xarray()
    dataset.attrs["title"] = sweep["title"]
    dataset.attrs["case"] = sweep["case"]
    dataset.attrs["sweep_file"] = sweep["sweep_file"]
    for name, unit in units.items():
        dataset[name].attrs["units"] = unit
    return dataset


def gather(directory):
    """Writes results.csv, results.nc and results.png into the sweep's output directory, all or
    none: a gathering that fails leaves the previous results as they were (see `replacing`)."""
    directory = Path(directory)
    sweep = read_sweep(directory)
    frame, units = table(directory)
    names = ["results.csv", "results.nc"] + (["results.png"] if sweep.get("gather") else [])
    with replacing(*(directory / name for name in names)) as temporaries:
        frame.to_csv(temporaries[0], index=False)
        to_xarray(frame, sweep, units).to_netcdf(temporaries[1], engine="h5netcdf")
        if sweep.get("gather"):
            plot(directory, frame=frame, units=units).savefig(temporaries[2], dpi=120, format="png")


@contextmanager
def replacing(*paths):
    """Temporary paths beside `paths` to write to, renamed over them when the block ends without
    an error and removed when it raises.

    A gathering can fail midway (a full disk, an unreadable history, an interrupt): writing the
    results in place would leave them deleted or half written, and the table of a long study is
    worth keeping until a complete new one is there. A rename within one directory is atomic, so
    a reader sees the old file or the new one, never a part.
    """
    temporaries = [path.with_name(f".{path.name}.{os.getpid()}.tmp") for path in paths]
    try:
        yield temporaries
        for temporary, path in zip(temporaries, paths):
            os.replace(temporary, path)
    finally:
        for temporary in temporaries:
            temporary.unlink(missing_ok=True)


def open_sweep(directory, form="xarray"):
    """The results of a sweep: an xarray Dataset on the parameters, or (form="pandas") the table."""
    directory = Path(directory)
    sweep = read_sweep(directory)
    frame, units = table(directory)
    if form == "pandas":
        return frame
    if form != "xarray":
        raise ValueError(f"form must be 'xarray' or 'pandas', not {form!r}")
    return to_xarray(frame, sweep, units)


def plot(directory, frame=None, units=None, x=None, quantities=None):
    """A figure with each gathered quantity (default: all) against parameter `x` (default: the
    one with the most values), one line per combination of the other parameters' values."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    directory = Path(directory)
    sweep = read_sweep(directory)
    if frame is None:
        frame, units = table(directory)
    parameters = list(sweep["parameters"])
    if x is None:
        x = max(parameters, key=lambda p: frame[p].nunique())
    others = [p for p in parameters if p != x]
    names = [g["name"] for g in sweep.get("gather", [])]
    if quantities:
        unknown = [q for q in quantities if q not in names]
        if unknown:
            raise ValueError(f"{directory}: the sweep gathers no {', '.join(unknown)} (it gathers {', '.join(names)})")
        names = list(quantities)
    if x not in parameters:
        raise ValueError(f"{directory}: {x!r} is not a parameter of the sweep ({', '.join(parameters)})")
    figure, axes = plt.subplots(len(names), 1, figsize=(6.0, 3.2 * len(names)), squeeze=False)
    if not others:
        groups = [((), frame)]
    else:
        groups = frame.groupby(others if len(others) > 1 else others[0])
    for ax, name in zip(axes[:, 0], names):
        for key, group in groups:
            key = key if isinstance(key, tuple) else (key,)
            label = ", ".join(f"{p.split('.')[-1]} = {v}" for p, v in zip(others, key)) or None
            ordered = group.sort_values(x)
            ax.plot(ordered[x], ordered[name], marker="o", label=label)
        ax.set_ylabel(f"{name} ({(units or {}).get(name, '-')})")
        ax.grid(True, alpha=0.3)
        if others:
            ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel(x)
    figure.suptitle(sweep["title"], fontsize=10)
    figure.tight_layout(rect=(0.0, 0.0, 1.0, 1.0 - 0.3 / (3.2 * len(names))))
    return figure
