"""The grid snapshots of a run (grid.pvd and its grid_NNNNNN.vtr files), written where the case
sets `[output] grid_snapshots = true`: the nodes of the (moving) grid with their mass and velocity,
and the contact of the last step at each node (docs/case-format.md).

`contact_profile` gives the traction along one contact surface, node by node: along a pile's
faces, the radial stress and the shaft friction whose sums the history's reactions are.

Needs numpy and VTK (`vtkmodules`); pandas for the profile.
"""
import numpy as np

from .files import snapshots_path
from .snapshots import COMPONENTS, LazyFile, TimeOrdered, read_pvd, read_xml


def read_vtr(path):
    """(r node coordinates, y node coordinates, {name: point array}, {name: field data strings})
    of one grid .vtr; point k is node (k % len(r), k // len(r))."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLRectilinearGridReader

    grid, arrays, fields = read_xml(path, vtkXMLRectilinearGridReader, "rectilinear grid (.vtr)")
    r = vtk_to_numpy(grid.GetXCoordinates()).copy()
    y = vtk_to_numpy(grid.GetYCoordinates()).copy()
    return r, y, arrays, fields


class GridSnapshot(LazyFile):
    """One grid snapshot: `time` (s), `path`, and once read, `r` and `y` (the node coordinates of
    each axis, m), `arrays` ({name: array over the nodes, r fastest}) and `surface_names` (the
    contact surfaces, "<structure>/<surface>", that `contact_surface` indexes)."""

    reader = staticmethod(read_vtr)

    @property
    def r(self):
        return self._load()[0]

    @property
    def y(self):
        return self._load()[1]

    @property
    def surface_names(self):
        return self._names("contact_surface_names")

    def contact_profile(self, surface):
        """The nodes whose outline share lies mostly on `surface` ("<structure>/<surface>", or the
        surface's name alone where one structure has it), as a pandas DataFrame ordered by y then r:
        r, y (m), force_r, force_y, force_theta (the soil's force on the structure at the node over
        the last step, N [/rad]), traction_r, traction_y, traction_theta (that force over the node's
        share of the outline, Pa; soil pressing on a face gives a traction against its outward normal)
        and state (0 free, 1 sliding, 2 sticking)."""
        import pandas as pd

        if "contact_surface" not in self.arrays:
            raise KeyError(f"{self.path} has no contact arrays (the case has no contact, or the file "
                           "was written before grid snapshots held them)")
        names = self.surface_names
        matches = [k for k, name in enumerate(names) if name == surface or name.split("/", 1)[-1] == surface]
        if len(matches) != 1:
            found = "no" if not matches else "more than one"
            raise KeyError(f"{self.path}: {found} contact surface {surface!r}; it has: " + ", ".join(names))
        nodes = np.flatnonzero(self.arrays["contact_surface"] == matches[0])
        nr = len(self.r)
        frame = {"r": self.r[nodes % nr], "y": self.y[nodes // nr]}
        for name, prefix in (("contact_force", "force"), ("contact_traction", "traction")):
            for k, component in enumerate(COMPONENTS):
                frame[f"{prefix}_{component}"] = self.arrays[name][nodes, k]
        frame["state"] = self.arrays["contact_state"][nodes]
        return pd.DataFrame(frame).sort_values(["y", "r"], ignore_index=True)


class GridSnapshots(TimeOrdered):
    """The grid snapshots of a run in time order (a list of `GridSnapshot`), with `times` and `at`."""


def open_grid_snapshots(path):
    """The grid snapshots of a run: its directory, its grid.pvd, or a single .vtr (then one snapshot
    of time NaN). Nothing is read from the .vtr files until asked for."""
    path = snapshots_path(path, "grid.pvd")
    if path.suffix == ".vtr":
        return GridSnapshots([GridSnapshot(float("nan"), path)])
    return GridSnapshots(GridSnapshot(time, file) for time, file in read_pvd(path))
