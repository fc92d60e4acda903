"""open_snapshots and follow_particle: particles followed by id across re-sorted snapshots."""
import re

import numpy as np
import pytest
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import VTK_INT, vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import VTK_VERTEX, vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

import mpile
from mpile.files import RunFileError


def write_vtu(path, ids, r, y, sigma_ry):
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.column_stack([r, y, np.zeros_like(r)]), deep=True))
    cells = vtkCellArray()
    for i in range(len(r)):
        cells.InsertNextCell(1, [i])
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(VTK_VERTEX, cells)
    for name, values, kind in [("sigma_ry", np.asarray(sigma_ry, float), None),
                               ("id", np.asarray(ids, np.int32), VTK_INT)]:
        array = numpy_to_vtk(values, deep=True, array_type=kind)
        array.SetName(name)
        grid.GetPointData().AddArray(array)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(grid)
    assert writer.Write() == 1


@pytest.fixture
def shuffled_run(tmp_path):
    """Three snapshots (t = 0, 1, 2 s) of particles 0..4, each in another order; particle k sits at
    r = k + t, y = 10 k, with sigma_ry = 100 k + t. Particle 5 appears at t = 2 s (a split)."""
    rng = np.random.default_rng(7)
    entries = []
    for index, t in enumerate((0.0, 1.0, 2.0)):
        ids = np.arange(6 if t == 2.0 else 5)
        ids = ids[rng.permutation(len(ids))]
        name = f"particles_{index:06d}.vtu"
        write_vtu(tmp_path / name, ids, ids + t, 10.0 * ids, 100.0 * ids + t)
        entries.append(f'<DataSet timestep="{t:g}" group="" part="0" file="{name}"/>')
    # Listed out of time order on purpose: the sequence is sorted by time.
    entries = [entries[2], entries[0], entries[1]]
    (tmp_path / "particles.pvd").write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">'
                                            "<Collection>" + "".join(entries) + "</Collection></VTKFile>\n")
    return tmp_path


def test_follow_a_particle_by_id(shuffled_run):
    snapshots = mpile.open_snapshots(shuffled_run)
    assert list(snapshots.times) == [0.0, 1.0, 2.0]
    track = mpile.follow_particle(snapshots, 3)
    assert list(track.index) == [0.0, 1.0, 2.0]
    assert list(track["r"]) == [3.0, 4.0, 5.0]
    assert list(track["y"]) == [30.0, 30.0, 30.0]
    assert list(track["sigma_ry"]) == [300.0, 301.0, 302.0]
    split = mpile.follow_particle(shuffled_run, 5, ["sigma_ry"])  # a directory works too
    assert list(split.index) == [2.0] and list(split["sigma_ry"]) == [502.0]
    with pytest.raises(KeyError, match="id 9"):
        mpile.follow_particle(snapshots, 9)
    with pytest.raises(KeyError, match="no point array sigma_zz; it has: sigma_ry, id"):
        mpile.follow_particle(snapshots, 3, ["sigma_zz"])


def test_dataset_on_time_and_id(shuffled_run):
    ds = mpile.open_snapshots(shuffled_run).to_xarray(["sigma_ry"])
    assert list(ds["id"].values) == [0, 1, 2, 3, 4, 5]
    np.testing.assert_array_equal(ds["r"].sel(id=2).values, [2.0, 3.0, 4.0])
    np.testing.assert_array_equal(ds["sigma_ry"].sel(time=1.0).values[:5], 100.0 * np.arange(5) + 1.0)
    assert np.isnan(ds["sigma_ry"].sel(id=5).values[:2]).all() and ds["sigma_ry"].sel(id=5).values[2] == 502.0
    assert ds["sigma_ry"].attrs["units"] == "Pa"


def test_snapshot_table(shuffled_run):
    frame = mpile.open_snapshots(shuffled_run)[0].to_frame()
    assert frame.index.name == "id"
    assert frame.loc[4, "r"] == 4.0 and frame.loc[4, "sigma_ry"] == 400.0


def test_refuses_missing_and_foreign_files(tmp_path):
    with pytest.raises(RunFileError, match="holds no particles.pvd"):
        mpile.open_snapshots(tmp_path)
    with pytest.raises(RunFileError, match="gone.pvd"):
        mpile.open_snapshots(tmp_path / "gone.pvd")
    bad = tmp_path / "bad.pvd"
    bad.write_text("<VTKFile type='UnstructuredGrid'></VTKFile>")
    with pytest.raises(RunFileError, match="bad.pvd is not a .pvd collection"):
        mpile.open_snapshots(bad)
    broken = tmp_path / "broken.pvd"
    broken.write_text("<VTKFile")
    with pytest.raises(RunFileError, match="broken.pvd is not a readable"):
        mpile.open_snapshots(broken)
    (tmp_path / "lost.pvd").write_text('<VTKFile type="Collection"><Collection>'
                                       '<DataSet timestep="0" file="nowhere.vtu"/></Collection></VTKFile>')
    with pytest.raises(RunFileError, match="nowhere.vtu: no such file"):
        mpile.open_snapshots(tmp_path / "lost.pvd")[0].arrays


def test_real_run_follows_a_sliding_particle(real_run):
    """V7: the block slides down the incline. Particles are re-sorted between snapshots, so a
    particle followed by position in the arrays would jump; followed by id, its path from the
    first snapshot equals the displacement the solver wrote for it."""
    snapshots = mpile.open_snapshots(real_run)
    assert len(snapshots) == 5 and snapshots.times[-1] == pytest.approx(1.0)
    first, last = snapshots[0], snapshots[-1]
    assert last.body_names == ["block", "incline"]
    assert not np.array_equal(first.arrays["id"], last.arrays["id"])  # re-sorted: the test means something
    block = first.arrays["id"][first.arrays["body"] == 0]
    for particle in block[:: max(1, len(block) // 10)]:
        track = mpile.follow_particle(snapshots, int(particle), ["body"])
        assert len(track) == 5 and (track["body"] == 0).all()
        frame = last.to_frame()
        # displacement = r - r0 in the solver; round-off of the subtraction only.
        assert track["r"].iloc[-1] - track["r"].iloc[0] == pytest.approx(frame.loc[particle, "displacement_r"],
                                                                         abs=1e-12)
        # The reference slide s(1 s) = 1.1781 m; docs/verification.md holds V7 to 3 %.
        assert track["r"].iloc[-1] - track["r"].iloc[0] == pytest.approx(1.1781, rel=0.03)


def test_vertical_force_across_sections(tmp_path):
    """Soil particles on a 1 cm grid over r in [0, 0.5] m, y in [0, 1] m, with axisymmetric volumes
    (r dr dy, per radian) and sigma_yy = -(100 kPa + 50 kPa/m * y); a rigid block beside them at
    1e9 Pa. Across y the soil between r_min and r_max carries (100 kPa + 50 kPa/m * y) (r_max^2 - r_min^2) / 2:
    the particles' r are cell centres (the midpoint rule is exact for the integrand r) and a slab of
    three rows centred on a row averages the linear stress exactly, so only round-off is allowed."""
    h = 0.01
    r, y = [a.ravel() for a in np.meshgrid((np.arange(50) + 0.5) * h, (np.arange(100) + 0.5) * h)]
    rigid_r, rigid_y = [a.ravel() for a in np.meshgrid(0.505 + np.arange(3) * h, (np.arange(100) + 0.5) * h)]
    all_r, all_y = np.concatenate([r, rigid_r]), np.concatenate([y, rigid_y])
    sigma_yy = np.concatenate([-(1e5 + 5e4 * y), np.full(rigid_r.size, -1e9)])
    material = np.concatenate([np.zeros(r.size), np.ones(rigid_r.size)]).astype(np.int32)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.column_stack([all_r, all_y, np.zeros_like(all_r)]), deep=True))
    cells = vtkCellArray()
    for i in range(all_r.size):
        cells.InsertNextCell(1, [i])
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(VTK_VERTEX, cells)
    for name, values, kind in [("sigma_yy", sigma_yy, None), ("volume", all_r * h * h, None),
                               ("material", material, VTK_INT)]:
        array = numpy_to_vtk(values, deep=True, array_type=kind)
        array.SetName(name)
        grid.GetPointData().AddArray(array)
    names = vtkStringArray()
    names.SetName("material_names")
    for name in ("sand", "pile (rigid)"):
        names.InsertNextValue(name)
    grid.GetFieldData().AddArray(names)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(str(tmp_path / "column.vtu"))
    writer.SetInputData(grid)
    assert writer.Write() == 1

    snapshot = mpile.open_snapshots(tmp_path / "column.vtu")[0]
    heights = np.array([0.205, 0.505, 0.805])
    expected = (1e5 + 5e4 * heights) * (0.3**2 - 0.1**2) / 2
    np.testing.assert_allclose(snapshot.vertical_force(heights, 0.1, 0.3, slab=3 * h), expected, rtol=1e-12)
    whole = (1e5 + 5e4 * heights) * 0.5**2 / 2  # the rigid block's 1e9 Pa is left out
    np.testing.assert_allclose(snapshot.vertical_force(heights, slab=3 * h), whole, rtol=1e-12)
    with pytest.raises(ValueError, match="slab must be positive"):
        snapshot.vertical_force(0.5, slab=0.0)


@pytest.mark.parametrize("cut_at, problem", [
    ("half", r"Cannot read .* too short|not long enough"),       # in the appended data
    (b"<PointData", r"Error parsing XML in stream at line \d+"),  # in the XML header
])
def test_truncated_snapshot_is_refused(tmp_path, capfd, cut_at, problem):
    """A .vtu cut short (a run stopped while writing it, a partial copy): VTK reports errors and
    returns an empty data set, which must not pass for a snapshot without particles. The error
    names the file and VTK's reason, and VTK's own messages are not printed besides."""
    whole = tmp_path / "particles_000000.vtu"
    ids = np.arange(200)
    write_vtu(whole, ids, ids * 0.01, ids * 0.02, ids * 1.0)
    data = whole.read_bytes()
    end = len(data) // 2 if cut_at == "half" else data.index(cut_at) + len(cut_at)
    cut = tmp_path / "cut.vtu"
    cut.write_bytes(data[:end])
    snapshot = mpile.open_snapshots(cut)[0]  # nothing read yet
    with pytest.raises(RunFileError, match=r"cut\.vtu is not a readable VTK XML unstructured grid \(\.vtu\), "
                                           r"cut short or damaged: .*(" + problem + ")"):
        snapshot.positions
    assert "ERR|" not in capfd.readouterr().err
    assert mpile.open_snapshots(whole)[0].positions.shape == (200, 2)  # the whole file still reads


def cut_short(whole, directory):
    """Copies of the file `whole` cut at every length from its appended data's start to 300 bytes
    into it (where VTK reads some cuts without an error and returns no points) and at half its
    length, as (length, path)."""
    data = whole.read_bytes()
    start = data.index(b"<AppendedData")
    for end in sorted(set(range(start, min(start + 300, len(data)))) | {len(data) // 2}):
        cut = directory / f"cut{whole.suffix}"
        cut.write_bytes(data[:end])
        yield end, cut


def test_a_real_snapshot_cut_short_anywhere_is_refused(real_run, tmp_path):
    """A run's .vtu cut short in its appended data: every cut raises RunFileError naming the file,
    including those after which VTK reports no error but reads none of the declared points."""
    whole = sorted(real_run.glob("particles_*.vtu"))[-1]
    points = len(mpile.open_snapshots(whole)[0].positions)
    assert points > 100
    opened, messages = [], []
    for end, cut in cut_short(whole, tmp_path):
        try:
            snapshot = mpile.open_snapshots(cut)[0]
            opened.append((end, len(snapshot.positions)))
        except RunFileError as error:
            messages.append(str(error))
    assert opened == [], f"cut at these lengths, {whole.name} opened with (length, points): {opened}"
    pattern = re.compile(r"cut\.vtu is not a readable VTK XML unstructured grid \(\.vtu\), cut short or damaged: ")
    assert all(pattern.search(message) for message in messages), messages[:3]
    assert any(f"it declares {points} points and 0 were read" in message for message in messages)
