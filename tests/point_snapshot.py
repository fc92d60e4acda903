"""A particle snapshot as mpile writes one (.vtu: vertex cells, point arrays), written from numpy
arrays, for the tests of the tools that read snapshots."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import VTK_INT, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_VERTEX, vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter


def write_point_snapshot(path, r, y, arrays, who):
    """Particles at (r, y) with `arrays` {name: values}, integer arrays written as VTK ints; exits
    naming `who` when the file cannot be written."""
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.column_stack([r, y, np.zeros_like(r)]), deep=True))
    cells = vtkCellArray()
    for i in range(len(r)):
        cells.InsertNextCell(1, [i])
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(VTK_VERTEX, cells)
    for name, values in arrays.items():
        values = np.asarray(values)
        kind = VTK_INT if values.dtype.kind == "i" else None
        array = numpy_to_vtk(values, deep=True, array_type=kind)
        array.SetName(name)
        grid.GetPointData().AddArray(array)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(grid)
    if writer.Write() != 1:
        sys.exit(f"{who}: cannot write {path}")
