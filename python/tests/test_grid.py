"""open_grid_snapshots and contact_profile on a real run: a soil column resting on a rigid floor
(tests/data/column_on_floor.toml)."""
import subprocess

import numpy as np
import pytest

import mpile
from conftest import REPOSITORY, mpile_binary
from mpile.files import RunFileError
from test_snapshots import cut_short


@pytest.fixture(scope="module")
def column_run(tmp_path_factory):
    binary = mpile_binary()
    if binary is None:
        pytest.skip("no mpile program: set MPILE to its path (ctest does)")
    directory = tmp_path_factory.mktemp("column")
    case = REPOSITORY / "tests" / "data" / "column_on_floor.toml"
    subprocess.run([binary, "run", str(case), "--out", str(directory / "run"), "--threads", "1"],
                   check=True, capture_output=True, timeout=300)
    return directory / "run"


def test_floor_carries_the_column_as_a_uniform_traction(column_run):
    grid = mpile.open_grid_snapshots(column_run)
    assert grid.times[0] == 0.0 and len(grid) >= 2
    last = grid[-1]
    assert last.surface_names == ["floor/top"]
    profile = last.contact_profile("top")  # the surface's name alone, as one structure has it
    np.testing.assert_array_equal(profile["r"], np.arange(9) / 8.0)
    assert (profile["y"] == 0.5).all() and (profile["state"] > 0).all()
    # rho g H downward on the floor, off the face's two ends; 1 % covers the particles' quadrature
    # in r and the phase's equilibrium tolerance (the C++ test's reasoning).
    inner = profile.iloc[1:-1]
    np.testing.assert_allclose(inner["traction_y"], -1650.0 * 9.81, rtol=0.01)
    assert np.abs(inner["traction_r"]).max() < 0.01 * 1650.0 * 9.81
    # The node forces add up to the column's weight per radian, rho g H R^2 / 2.
    assert profile["force_y"].sum() == pytest.approx(-1650.0 * 9.81 * 0.5, rel=0.01)
    same = mpile.open_grid_snapshots(column_run / "grid.pvd").at(last.time)
    assert same.path == last.path


def test_refuses_what_it_cannot_read(column_run, tmp_path):
    with pytest.raises(RunFileError, match="holds no grid.pvd .written with \\[output\\] grid_snapshots"):
        mpile.open_grid_snapshots(tmp_path)
    with pytest.raises(KeyError, match="no contact surface 'tip'; it has: floor/top"):
        mpile.open_grid_snapshots(column_run)[-1].contact_profile("tip")
    wrong = tmp_path / "grid_000000.vtr"
    wrong.write_text("not a grid")
    with pytest.raises(RunFileError, match="is not a VTK XML rectilinear grid"):
        mpile.open_grid_snapshots(wrong)[0].r


def test_a_real_grid_snapshot_cut_short_anywhere_is_refused(column_run, tmp_path):
    """A grid .vtr cut short in its appended data raises RunFileError naming the file at every
    cut, including those after which VTK reports no error and returns no coordinates."""
    whole = sorted(column_run.glob("grid_*.vtr"))[-1]
    nodes = len(mpile.open_grid_snapshots(whole)[0].r) * len(mpile.open_grid_snapshots(whole)[0].y)
    opened, messages = [], []
    for end, cut in cut_short(whole, tmp_path):
        try:
            opened.append((end, len(mpile.open_grid_snapshots(cut)[0].r)))
        except RunFileError as error:
            messages.append(str(error))
    assert opened == [], f"cut at these lengths, {whole.name} opened with (length, r nodes): {opened}"
    assert all("cut.vtr is not a readable VTK XML rectilinear grid (.vtr), cut short or damaged: " in message
               for message in messages), messages[:3]
    assert any(f"it declares {nodes} points and 0 were read" in message for message in messages)
