"""open_grid_snapshots and contact_profile on a real run: a soil column resting on a rigid floor."""
import subprocess

import numpy as np
import pytest

import mpile
from conftest import mpile_binary
from mpile.files import RunFileError

# An elastic column 1 m high and 1 m in radius (roller at r = 1 m) on a rigid floor held still,
# brought to rest by local damping, with grid snapshots (the case of the C++ test
# VtkOutput.GridSnapshotHoldsTheContactTractionUnderASoilColumn).
COLUMN = """geometry = "axisymmetric"
title = "column on a floor"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 8 }]
y = [{ start = 0.0, end = 2.0, cells = 16 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 20e6
poisson_ratio = 0.0
density = 1650.0
[materials.steel]
type = "linear_elastic"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0
[[bodies]]
name = "soil"
material = "soil"
region = { r = [0.0, 1.0], y = [0.5, 1.5] }
[[bodies]]
name = "floor"
material = "steel"
region = { r = [0.0, 1.0], y = [0.25, 0.5] }
[bodies.rigid]
velocity_y = 0.0
[[contact]]
structure = "floor"
surfaces = { top = "top" }
[boundaries]
r_max = "roller"
y_min = "fixed"
[solver]
gravity = [0.0, -9.81]
[[phases]]
name = "settle"
duration = 2.0
local_damping = 0.7
equilibrium_tolerance = 1e-3
[output]
grid_snapshots = true
snapshot_interval = 0.05
"""


@pytest.fixture(scope="module")
def column_run(tmp_path_factory):
    binary = mpile_binary()
    if binary is None:
        pytest.skip("no mpile program: set MPILE to its path (ctest does)")
    directory = tmp_path_factory.mktemp("column")
    (directory / "column.toml").write_text(COLUMN)
    subprocess.run([binary, "run", str(directory / "column.toml"), "--out", str(directory / "run"),
                    "--threads", "1"], check=True, capture_output=True, timeout=300)
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
