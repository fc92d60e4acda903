"""Radiated energy and peak particle velocity of an installation, on histories whose values are known."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.files import RunFileError


def history(tmp_path, radiated=True):
    # Rows 0-1 held (phase 0), rows 2-5 the installation; the pile gains 0.2 m from row 1.
    series = {"/time": ([0.0, 1.0, 2.0, 3.0, 4.0, 5.0], "s"),
              "/phase": (np.array([0, 0, 1, 1, 1, 1]), "-"),
              "/bodies/pile/penetration": ([0.0, 0.05, 0.1, 0.15, 0.2, 0.25], "m"),
              "/monitors/near/v_r": ([9.0, 9.0, 0.3, 0.0, -0.6, 0.0], "m/s"),
              "/monitors/near/v_y": ([9.0, 9.0, 0.4, 0.0, 0.8, 0.1], "m/s"),
              "/monitors/near/v_theta": ([9.0, 9.0, 0.0, 1.2, 0.0, 0.0], "m/s")}
    if radiated:
        series["/energy/radiated"] = ([0.0, 2.0, 3.0, 5.0, 8.0, 12.0], "J/rad")
    return write_history(tmp_path / "history.h5", series)


def test_radiated_energy_and_ppv_over_the_installation(tmp_path):
    r = mpile.radiation(history(tmp_path))
    # From the held phase's last row: 12 - 2 J/rad over 0.25 - 0.05 m.
    assert r.penetration == pytest.approx(0.2, rel=1e-12)
    assert r.radiated == pytest.approx(10.0, rel=1e-12)
    assert r.radiated_per_metre == pytest.approx(50.0, rel=1e-12)
    # The peak of |v| over the installation only (the held rows' 9 m/s stay out): |(0, 0, 1.2)|
    # beats |(-0.6, 0.8, 0)| = 1.0.
    assert r.ppv == {"near": pytest.approx(1.2, rel=1e-12)}


def test_a_run_without_absorbing_faces_radiates_nothing_known(tmp_path):
    r = mpile.radiation(history(tmp_path, radiated=False))
    assert np.isnan(r.radiated) and np.isnan(r.radiated_per_metre)
    assert r.ppv["near"] == pytest.approx(1.2, rel=1e-12)


def test_a_missing_monitor_is_named(tmp_path):
    with pytest.raises(RunFileError, match="has no dataset /monitors/far/v_r"):
        mpile.radiation(history(tmp_path), monitors=["far"])


def test_the_table_tool_prints_the_row(tmp_path):
    import subprocess
    import sys
    from conftest import REPOSITORY

    path = history(tmp_path)
    done = subprocess.run([sys.executable, str(REPOSITORY / "tools" / "vibration_table.py"), f"{path}:known",
                           "--monitors", "near"], capture_output=True, text=True, check=True)
    assert done.stdout.splitlines()[-1] == "| known | 0.2000 | 10 | 50 | 1.2e+03 |"
