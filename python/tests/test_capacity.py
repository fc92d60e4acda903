"""The load test of a run: load-settlement curve of its last phase and the capacity at 10 % of D."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.capacity import load_test
from mpile.files import RunFileError

CASE = '[monopile]\ndiameter = 0.5\n[[phases]]\nname = "install"\n[[phases]]\nname = "load_test"\n'


def history(tmp_path):
    # Two rows of the installation (0.1 m reached), then the load test: the pile goes from 0.1 to
    # 0.16 m while the drive's force rises linearly, 1 kN/rad per mm of settlement (driving_F_y
    # is upward positive: the load is its negative).
    depth = np.array([0.0, 0.1, 0.11, 0.12, 0.14, 0.16])
    force = np.array([0.0, -5e3, -10e3, -20e3, -40e3, -60e3])
    return write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0, 2.0, 3.0, 4.0, 5.0], "s"), "/phase": (np.array([0, 0, 1, 1, 1, 1]), "-"),
        "/bodies/pile/penetration": (depth, "m"), "/bodies/pile/driving_F_y": (force, "N/rad")},
        attrs={"case_resolved": CASE, "title": "known"},
        phases=[{"name": "install", "start": 0.0, "end": 1.0, "ended": "at pile penetration 0.1 m"},
                {"name": "load_test", "start": 1.0, "end": 5.0, "ended": "at pile settlement 0.06 m"}])


def test_load_settlement_and_capacity_at_a_tenth_of_the_diameter(tmp_path):
    t = load_test(history(tmp_path))
    assert t.label == "known" and t.diameter == 0.5
    assert t.ended == "at pile settlement 0.06 m"
    assert t.settlement == pytest.approx([0.01, 0.02, 0.04, 0.06], rel=1e-12)
    assert t.load == pytest.approx([10.0, 20.0, 40.0, 60.0], rel=1e-12)
    # 10 % of 0.5 m = 0.05 m, between the rows at 0.04 and 0.06 m: 50 kN/rad.
    assert t.capacity == pytest.approx(50.0, rel=1e-12)
    assert t.load_at(0.03) == pytest.approx(30.0, rel=1e-12)
    assert np.isnan(t.load_at(0.07))  # beyond the test


def test_a_smaller_given_diameter_and_a_test_stopped_short(tmp_path):
    path = history(tmp_path)
    assert load_test(path, diameter=0.3).capacity == pytest.approx(30.0, rel=1e-12)
    assert np.isnan(load_test(path, diameter=1.0).capacity)  # 0.1 m never reached


def test_a_missing_body_is_named(tmp_path):
    with pytest.raises(RunFileError, match="has no dataset /bodies/caisson/penetration"):
        load_test(history(tmp_path), body="caisson")


def test_the_tool_prints_the_capacity_and_draws_the_curve(tmp_path):
    import subprocess
    import sys
    from conftest import REPOSITORY

    path = history(tmp_path)
    figure = tmp_path / "capacity.png"
    done = subprocess.run([sys.executable, str(REPOSITORY / "tools" / "capacity.py"), f"{path}:known",
                           "--out", str(figure)], capture_output=True, text=True, check=True)
    # 50 kN/rad, 2 pi x 50 kN = 0.314 MN for the whole pile.
    assert "| known | 0.0600 | 50.0 | 0.314 | at pile settlement 0.06 m |" in done.stdout.splitlines()
    assert figure.stat().st_size > 10000
