"""Shared runs for the tests: the synthetic monopile run whose values are known exactly
(tests/make_monopile_history.py), histories written here with h5py, and one real mpile run.

The package is imported from this repository (python/), not from an installed copy, so that the
tests check the code beside them; test_install.py checks the installed package separately.
"""
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

PYTHON_DIR = Path(__file__).resolve().parent.parent
REPOSITORY = PYTHON_DIR.parent
sys.path.insert(0, str(PYTHON_DIR))


@pytest.fixture(scope="session")
def synthetic_run(tmp_path_factory):
    """tests/make_monopile_history.py's run: a pile held for 0.5 s then driven down at 0.1 m/s for
    5 s, with forces linear in penetration, and two particle snapshots."""
    out = tmp_path_factory.mktemp("synthetic") / "run"
    subprocess.run([sys.executable, str(REPOSITORY / "tests" / "make_monopile_history.py"), str(out)],
                   check=True, capture_output=True)
    return out


def mpile_binary():
    """The mpile program: $MPILE (ctest sets it to the built target), else the release build."""
    path = os.environ.get("MPILE") or str(REPOSITORY / "build" / "release" / "bin" / "mpile")
    return path if os.access(path, os.X_OK) else None


@pytest.fixture(scope="session")
def real_run(tmp_path_factory):
    """V7 (an elastic block sliding 1 s down a rigid incline, plane strain; 0.3 s of computing):
    a real history with /phases, units and a contact surface, a row every step, and five
    snapshots with particle ids, body and material names, re-sorted between snapshots."""
    binary = mpile_binary()
    if binary is None:
        pytest.skip("no mpile program: set MPILE to its path (ctest does)")
    out = tmp_path_factory.mktemp("v7") / "run"
    case = REPOSITORY / "cases" / "verification" / "v7_block_on_incline.toml"
    subprocess.run([binary, "run", str(case), "--out", str(out), "--threads", "1", "--set",
                    "output.history_interval=0"], check=True, capture_output=True, timeout=300)
    return out


def write_history(path, series, units_key="units", attrs=None, phases=None):
    """A history.h5 from {path: (values, units)}, the units under `units_key`; `phases` is a list
    of attribute dicts written as /phases/<i>."""
    with h5py.File(path, "w") as history:
        for key, value in (attrs or {}).items():
            history.attrs[key] = value
        for name, (values, units) in series.items():
            history[name] = np.asarray(values)
            if units is not None:
                history[name].attrs[units_key] = units
        for index, table in enumerate(phases or []):
            group = history.create_group(f"/phases/{index}")
            for key, value in table.items():
                group.attrs[key] = value
    return path


@pytest.fixture
def small_history(tmp_path):
    """Three rows whose every value is known: two phases, a pile going down 1 mm per row."""
    return write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 0.5, 1.0], "s"),
        "/step": (np.array([0, 10, 20], dtype=np.int64), "-"),
        "/phase": (np.array([0, 1, 1], dtype=np.int64), "index into the case's [[phases]] and /phases"),
        "/bodies/pile/u_y": ([0.0, -0.001, -0.002], "m"),
        "/reactions/pile/tip/F_y": ([0.0, 100.0, 250.0], "N/rad"),
        "/energy/kinetic": ([1.0, 2.0, 3.0], "J/rad"),
    }, attrs={"title": "small", "status": "complete", "threads": 2.0,
              "case_text": '[[phases]]\nname = "hold"\n[[phases]]\nname = "push"\n'})


@pytest.fixture(autouse=True)
def _no_stray_files(request):
    """Tests write only to their temporary directories, never into the repository."""
    before = set(os.listdir(PYTHON_DIR))
    yield
    stray = set(os.listdir(PYTHON_DIR)) - before - {".pytest_cache", "__pycache__"}
    assert not stray, f"a test left {sorted(stray)} in {PYTHON_DIR}"

