"""The decisions of tools/paraview_open_run.py (array, pile, symmetric colour range, times),
made with numpy and VTK only, so they are tested here without ParaView."""
import subprocess
import sys

import numpy as np
import pytest
from conftest import REPOSITORY
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

from mpile.display import pile_bodies, rigid_bodies, symmetric_bound

sys.path.insert(0, str(REPOSITORY / "tools"))
import paraview_open_run  # noqa: E402

SCRIPT = REPOSITORY / "tools" / "paraview_open_run.py"


def test_symmetric_bound_and_rigid_bodies():
    assert symmetric_bound(np.arange(-100.0, 101.0)) == pytest.approx(99.0)  # 99th percentile of 0..100
    assert symmetric_bound(np.zeros(5)) == 1.0 and symmetric_bound([]) == 1.0
    assert symmetric_bound([np.nan, 2.0]) == pytest.approx(2.0)
    names, materials = ["soil", "plug", "pile"], ["sand", "pile (rigid)"]
    assert rigid_bodies(names, materials) == [2]
    assert pile_bodies(names, materials) == [2]
    assert pile_bodies(names, materials, ["plug", "0"]) == [1, 0]
    with pytest.raises(ValueError, match="no body named 'caisson'; the bodies are: soil, plug, pile"):
        pile_bodies(names, materials, ["caisson"])


def test_plan_of_the_synthetic_run(synthetic_run):
    """sigma_ry = 10 kPa/m (r + y - 1 m) on a 50 x 50 lattice, half of it at t = 0, the pile block
    (body 1, 1e9 Pa) hidden: the range is the 99th percentile of the soil's |sigma_ry| at 2.5 s."""
    decided = paraview_open_run.plan(synthetic_run, pile_body=["1"])
    centres = 0.01 + 0.02 * np.arange(50)
    r, y = (a.ravel() for a in np.meshgrid(centres, centres))
    soil = ~((r > 0.4) & (r < 0.6) & (y > 0.6))
    bound = np.percentile(np.abs(1e4 * (r + y - 1.0))[soil], 99)
    assert decided.colour_range == pytest.approx((-bound, bound), rel=1e-12)
    assert decided.times == [0.0, 2.5]
    assert decided.hidden == [1]
    assert decided.soil_particles == int(soil.sum()) == 2300
    assert decided.spacing == pytest.approx(0.02, rel=1e-9)
    assert decided.centre == pytest.approx((0.5, 0.5), rel=1e-9)
    # Without --pile-body and without body names there is nothing known to hide, and the pile's
    # 1e9 Pa then set the range: why the pile must be named or found.
    assert paraview_open_run.plan(synthetic_run).colour_range[1] == pytest.approx(1e9)


def test_plan_of_a_real_run(real_run):
    """V7: the incline is the rigid body (material "incline (rigid)"), the block the soil."""
    decided = paraview_open_run.plan(real_run)
    assert decided.hidden == [1] and decided.hidden_names == ["incline"]
    bounds = []
    for time, name in zip(decided.times, sorted(p.name for p in real_run.glob("particles_*.vtu"))):
        reader = vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(real_run / name))
        reader.Update()
        data = reader.GetOutput().GetPointData()
        sigma, body = (vtk_to_numpy(data.GetArray(n)) for n in ("sigma_ry", "body"))
        bounds.append(np.percentile(np.abs(sigma[body == 0]), 99))
    assert decided.colour_range == pytest.approx((-max(bounds), max(bounds)), rel=1e-12)
    assert decided.times == pytest.approx([0.0, 0.25, 0.5, 0.75, 1.0], abs=1e-9)  # snapshot_interval 0.25 s
    assert decided.soil_particles == 200  # the 1 m x 0.5 m block, 0.1 m cells, 2 x 2 per cell


def test_script_prints_the_plan_and_refuses_bad_input(synthetic_run):
    run = subprocess.run([sys.executable, str(SCRIPT), str(synthetic_run), "--pile-body", "1", "--plan-only"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "times: 0, 2.5 s\ncolour: sigma_ry on Cool to Warm, -9000 to 9000\npile hidden: body 1 (1)\n" in run.stdout
    bad = subprocess.run([sys.executable, str(SCRIPT), str(synthetic_run), "--array", "sigma_zz", "--plan-only"],
                         capture_output=True, text=True)
    assert bad.returncode == 2
    assert "has no scalar point array sigma_zz; it has: sigma_ry, body, material" in bad.stderr
    # Without ParaView the pipeline cannot be built: said so, not a traceback.
    if subprocess.run([sys.executable, "-c", "import paraview.simple"], capture_output=True).returncode != 0:
        missing = subprocess.run([sys.executable, str(SCRIPT), str(synthetic_run)], capture_output=True, text=True)
        assert missing.returncode == 2 and "pvpython" in missing.stderr
