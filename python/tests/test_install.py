"""The package installs with pip offline into a virtual environment and imports from outside the
repository, as docs/python.md tells researchers to do it."""
import importlib
import os
import shutil
import subprocess
import sys

import pytest
from conftest import PYTHON_DIR

import mpile


def test_every_exported_name_is_what_it_says():
    """A submodule named like a function would shadow it once imported: import them all first."""
    for module in ("files", "history", "phase_table", "snapshots", "display", "monopile", "cases"):
        importlib.import_module(f"mpile.{module}")
    for name in mpile.__all__:
        value = getattr(mpile, name)
        assert not isinstance(value, type(mpile)), f"mpile.{name} is a module"


@pytest.mark.install
def test_pip_install_into_a_venv_then_import_from_elsewhere(tmp_path, synthetic_run):
    # From a copy, so that the build's own files (build/, mpile.egg-info) stay out of the repository.
    source = tmp_path / "source"
    shutil.copytree(PYTHON_DIR, source, ignore=shutil.ignore_patterns("__pycache__", ".pytest_cache", "build",
                                                                      "*.egg-info", "tests"))
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    environment = {**os.environ, "PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    environment.pop("PYTHONPATH", None)
    install = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-deps", str(source)],
                             capture_output=True, text=True, env=environment)
    assert install.returncode == 0, install.stdout + install.stderr
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    check = subprocess.run([str(python), "-c",
                            "import sys, mpile\n"
                            "print(mpile.__file__)\n"
                            f"ds = mpile.open_history({str(synthetic_run)!r})\n"
                            "print(ds.sizes['time'], ds.attrs['title'])\n"],
                           cwd=elsewhere, capture_output=True, text=True, env=environment)
    assert check.returncode == 0, check.stderr
    where, result = check.stdout.splitlines()
    assert where.startswith(str(venv)), f"imported {where}, not the installed copy"
    assert result == "551 synthetic monopile"
