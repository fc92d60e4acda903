"""The particle snapshots of a run (particles.pvd and its particles_NNNNNN.vtu files).

`open_snapshots` gives a sequence of `Snapshot`s in time order, each read from its .vtu only when
its data is first asked for (a long run has many large snapshots). A snapshot's particles are in
the solver's order of that moment: particles are re-sorted between snapshots, so a particle is
followed by its `id` (stable; a split particle keeps its id for one half and the other half gets a
new one), never by its position in the arrays. `follow_particle` does that; `Snapshots.to_xarray`
lays chosen arrays on dims (time, id).

Needs numpy and VTK (`vtkmodules`, Debian's python3-vtk9 or ParaView's own); pandas and xarray
only for the tables.
"""
import os
import re
import xml.etree.ElementTree as ElementTree
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .files import RunFileError, snapshots_path

# Vector point arrays (velocity, displacement) have three components in this order.
COMPONENTS = ("r", "y", "theta")


def read_pvd(path):
    """(time, .vtu path) of every data set a .pvd collection lists, in time order."""
    path = Path(path)
    try:
        tree = ElementTree.parse(path)
    except (ElementTree.ParseError, OSError) as error:
        raise RunFileError(f"{path} is not a readable .pvd collection ({error})") from None
    entries = [(float(d.get("timestep", "nan")), path.parent / d.get("file", ""))
               for d in tree.iter("DataSet")]
    if tree.getroot().get("type") != "Collection":
        raise RunFileError(f"{path} is not a .pvd collection (VTKFile type is not Collection)")
    return sorted(entries, key=lambda entry: entry[0])


def read_xml(path, reader_class, kind):
    """(data set, {name: point array}, {name: field data strings}) of one VTK XML file read by
    `reader_class` (`kind` names the format in the error), arrays in the file's order."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if not os.path.isfile(path):
        raise RunFileError(f"{path}: no such file")
    reader = reader_class()
    if not reader.CanReadFile(str(path)):
        raise RunFileError(f"{path} is not a VTK XML {kind}")
    errors = collect_errors(reader)
    with vtk_warnings() as warnings:
        reader.SetFileName(str(path))
        reader.Update()
    if errors:
        raise RunFileError(f"{path} is not a readable VTK XML {kind}, cut short or damaged: "
                           + "; ".join(errors))
    grid = reader.GetOutput()
    data = grid.GetPointData()
    problem = missing_points(reader, grid)
    if problem:
        raise RunFileError(f"{path} is not a readable VTK XML {kind}, cut short or damaged: {problem}"
                           + (" (VTK: " + "; ".join(warnings) + ")" if warnings else ""))
    arrays = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
    fields = {}
    field_data = grid.GetFieldData()
    for i in range(field_data.GetNumberOfArrays()):
        array = field_data.GetAbstractArray(i)
        if array.IsA("vtkStringArray"):
            fields[array.GetName()] = [array.GetValue(j) for j in range(array.GetNumberOfValues())]
    return grid, arrays, fields


def collect_errors(reader):
    """A list that gathers the error messages of a VTK XML `reader` and its XML parser, which are
    then no longer printed.

    Given a file cut short (a run stopped while writing it, a partial copy), the reader reports
    errors and returns an empty data set, which would pass for a snapshot without particles: the
    caller raises on any message instead. The pipeline's own "returned failure" that follows a
    parser error is silenced and left out, as it says nothing about the file.
    """
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand

    messages = []

    @calldata_type(VTK_STRING)
    def keep(caller, event, text):
        # VTK's text is "ERROR: In <source>, line <n>\n<class> (<address>): <message>".
        found = re.search(r"\(0x[0-9a-fA-F]+\): (.*)", text, re.DOTALL)
        messages.append(" ".join((found.group(1) if found else text).split()))

    tag = reader.AddObserver(vtkCommand.ErrorEvent, keep)
    reader.SetParserErrorObserver(reader.GetCommand(tag))
    reader.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda caller, event: None)
    return messages


def missing_points(reader, grid):
    """Why the data set `grid` that `reader` read lacks points its file declares, or "".

    Some cuts of a file (within its appended data, after the field data) are read without an
    error: VTK then returns no points, no coordinates and no arrays, which would pass for an empty
    snapshot. The file's header still declares how many points it has (a .vtu's NumberOfPoints, a
    .vtr's extent), and every point array holds one tuple per point.
    """
    declared = reader.GetNumberOfPoints()
    read = grid.GetNumberOfPoints()
    if read != declared:
        return f"it declares {declared} points and {read} were read"
    if grid.IsA("vtkRectilinearGrid"):
        for axis, coordinates, size in zip("xyz", (grid.GetXCoordinates(), grid.GetYCoordinates(),
                                                   grid.GetZCoordinates()), grid.GetDimensions()):
            if coordinates is None or coordinates.GetNumberOfTuples() != size:
                return f"its {axis} coordinates are missing or not {size} long"
    elif read and grid.GetPoints() is None:
        return f"it declares {declared} points and their coordinates were not read"
    data = grid.GetPointData()
    for i in range(data.GetNumberOfArrays()):
        array = data.GetAbstractArray(i)
        if array.GetNumberOfTuples() != read:
            return f"its point array {array.GetName()} has {array.GetNumberOfTuples()} values for {read} points"
    return ""


@contextmanager
def vtk_warnings():
    """A list that gathers the warnings VTK gives while the block runs (through its output window:
    a damaged file's parser warns about it), to be named in an error. VTK still prints them."""
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand, vtkOutputWindow

    messages = []

    @calldata_type(VTK_STRING)
    def keep(caller, event, text):
        found = re.search(r"\(0x[0-9a-fA-F]+\): (.*)", text, re.DOTALL)
        messages.append(" ".join((found.group(1) if found else text).split()))

    window = vtkOutputWindow.GetInstance()
    tag = window.AddObserver(vtkCommand.WarningEvent, keep)
    try:
        yield messages
    finally:
        window.RemoveObserver(tag)


def read_vtu(path):
    """(r-y positions as an (n, 2) array, {name: point array}, {name: field data strings}) of one
    .vtu, arrays in the file's order."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    grid, arrays, fields = read_xml(path, vtkXMLUnstructuredGridReader, "unstructured grid (.vtu)")
    points = grid.GetPoints()
    positions = vtk_to_numpy(points.GetData())[:, :2] if points is not None else np.zeros((0, 2))
    return positions, arrays, fields


class LazyFile:
    """A snapshot file at a `time` (s), read by the class's `reader` only when its data is first
    asked for. A reader returns the file's geometry, then {name: point array} and {name: field data
    strings}."""

    reader = None

    def __init__(self, time, path):
        self.time = time
        self.path = Path(path)
        self._data = None

    def _load(self):
        if self._data is None:
            self._data = type(self).reader(self.path)
        return self._data

    def __repr__(self):
        return f"{type(self).__name__}(time={self.time:g}, path={str(self.path)!r})"

    @property
    def arrays(self):
        return self._load()[-2]

    def _names(self, key):
        return self._load()[-1].get(key, [])


class Snapshot(LazyFile):
    """One particle snapshot: `time` (s), `path`, and once read, `positions` ((n, 2): r, y in m),
    `arrays` ({name: array}, stresses in Pa, compression negative), `body_names`, `material_names`."""

    reader = staticmethod(read_vtu)

    @property
    def positions(self):
        return self._load()[0]

    @property
    def body_names(self):
        """Names of the body indices of the array `body` (index k is body k); [] for files without."""
        return self._names("body_names")

    @property
    def material_names(self):
        """Names of the material indices; a rigid body's material is called "<body> (rigid)"."""
        return self._names("material_names")

    def scalars(self):
        """Names of the one-component point arrays, in the file's order."""
        return [name for name, values in self.arrays.items() if values.ndim == 1]

    def to_frame(self):
        """The snapshot as a pandas DataFrame, one row per particle: r, y, every scalar array, and
        each vector array as <name>_r, <name>_y, <name>_theta. Indexed by id where the file has it."""
        import pandas as pd

        columns = {"r": self.positions[:, 0], "y": self.positions[:, 1]}
        for name, values in self.arrays.items():
            if values.ndim == 1:
                columns[name] = values
            else:
                for k in range(values.shape[1]):
                    columns[f"{name}_{COMPONENTS[k] if k < len(COMPONENTS) else k}"] = values[:, k]
        frame = pd.DataFrame(columns)
        if "id" in frame:
            frame = frame.set_index("id")
        return frame

    def vertical_force(self, heights, r_min=0.0, r_max=np.inf, slab=0.01):
        """The vertical force the soil carries across horizontal sections, compression positive:
        at each height y (m), -sum(sigma_yy * volume) / slab over the deformable particles whose
        centre is within slab / 2 of y and whose r is in [r_min, r_max). That is the slab's mean of
        -integral sigma_yy r dr, in N per radian in an axisymmetric run (volumes are per radian) and N
        per metre in plane strain. Between r = 0 and a pile's inner radius it is the load the soil
        plug carries; a slab of at least a particle spacing keeps the count of particles steady."""
        if not slab > 0.0:
            raise ValueError(f"slab must be positive, not {slab}")
        for name in ("sigma_yy", "volume"):
            if name not in self.arrays:
                raise KeyError(f"{self.path} has no point array {name}; it has: " + ", ".join(self.scalars()))
        r, y = self.positions[:, 0], self.positions[:, 1]
        inside = (r >= r_min) & (r < r_max)
        inside &= ~rigid_particles(self)
        load = -self.arrays["sigma_yy"] * self.arrays["volume"]
        heights = np.atleast_1d(np.asarray(heights, float))
        return np.array([load[inside & (np.abs(y - h) < 0.5 * slab)].sum() / slab for h in heights])


def rigid_particles(snapshot):
    """A mask over a snapshot's particles (anything with `positions`, `material_names` and
    `arrays`): those of rigid bodies, whose materials are named "<body> (rigid)"; none where the
    snapshot has no material array."""
    if "material" not in snapshot.arrays:
        return np.zeros(len(snapshot.positions), dtype=bool)
    rigid = [k for k, name in enumerate(snapshot.material_names) if name.endswith("(rigid)")]
    return np.isin(snapshot.arrays["material"].astype(int), rigid)


class TimeOrdered(list):
    """Snapshots in time order, each with a `time` (s)."""

    @property
    def times(self):
        return np.array([snapshot.time for snapshot in self])

    def at(self, time):
        """The snapshot whose time is closest to `time` (s)."""
        if not self:
            raise IndexError("no snapshots")
        return min(self, key=lambda snapshot: abs(snapshot.time - time))


class Snapshots(TimeOrdered):
    """The snapshots of a run in time order (a list of `Snapshot`), with `times` and the tables below."""

    def to_xarray(self, arrays=("sigma_rr", "sigma_yy", "sigma_ry")):
        """The chosen scalar arrays and the positions r, y as an xarray Dataset on dims (time, id):
        NaN where a particle does not exist yet (made by a split later). Reads every snapshot."""
        import xarray as xr

        ids = np.unique(np.concatenate([_ids(snapshot) for snapshot in self])) if self else np.zeros(0, int)
        names = ["r", "y", *arrays]
        table = {name: np.full((len(self), len(ids)), np.nan) for name in names}
        for row, snapshot in enumerate(self):
            columns = np.searchsorted(ids, _ids(snapshot))
            table["r"][row, columns] = snapshot.positions[:, 0]
            table["y"][row, columns] = snapshot.positions[:, 1]
            for name in arrays:
                if name not in snapshot.arrays:
                    raise KeyError(f"{snapshot.path} has no point array {name}; it has: "
                                   + ", ".join(snapshot.scalars()))
                table[name][row, columns] = snapshot.arrays[name]
        units = {"r": "m", "y": "m"}
        return xr.Dataset({name: (("time", "id"), values, {"units": units.get(name, _units(name))})
                           for name, values in table.items()},
                          coords={"time": ("time", self.times, {"units": "s"}), "id": ids})


def _ids(snapshot):
    if "id" not in snapshot.arrays:
        raise KeyError(f"{snapshot.path} has no point array id (written by mpile since particle ids exist)")
    return snapshot.arrays["id"].astype(np.int64)


def _units(name):
    if name.startswith("sigma_") or name in ("p", "q"):
        return "Pa"
    return {"density": "kg/m^3"}.get(name, "")


def open_snapshots(path):
    """The particle snapshots of a run: its directory, its particles.pvd, or a single .vtu (then
    one snapshot of time NaN). Nothing is read from the .vtu files until asked for."""
    path = snapshots_path(path)
    if path.suffix == ".vtu":
        return Snapshots([Snapshot(float("nan"), path)])
    return Snapshots(Snapshot(time, file) for time, file in read_pvd(path))


def follow_particle(snapshots, particle_id, arrays=None):
    """One particle through the snapshots, as a pandas DataFrame indexed by time: r, y and the
    scalar arrays (`arrays`, default all). Snapshots in which the particle does not exist (before a
    split made it) are left out."""
    import pandas as pd

    if not isinstance(snapshots, list):
        snapshots = open_snapshots(snapshots)
    rows, times = [], []
    for snapshot in snapshots:
        where = np.flatnonzero(_ids(snapshot) == particle_id)
        if where.size == 0:
            continue
        i = where[0]
        names = arrays if arrays is not None else [n for n in snapshot.scalars() if n != "id"]
        row = {"r": snapshot.positions[i, 0], "y": snapshot.positions[i, 1]}
        for name in names:
            if name not in snapshot.arrays:
                raise KeyError(f"{snapshot.path} has no point array {name}; it has: " + ", ".join(snapshot.scalars()))
            row[name] = snapshot.arrays[name][i]
        rows.append(row)
        times.append(snapshot.time)
    if not rows:
        raise KeyError(f"no snapshot holds a particle with id {particle_id}")
    return pd.DataFrame(rows, index=pd.Index(times, name="time"))
