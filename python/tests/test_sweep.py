"""mpile.sweep.gather on a sweep's output directory written here (sweep.toml as `mpile sweep`
writes it, a history.h5 per variant): the previous results survive a gathering that fails, and a
[[gather]] name that cannot be a column is refused by name."""
import numpy as np
import pandas as pd
import pytest
import xarray as xr
from conftest import write_history

from mpile import sweep
from mpile.files import RunFileError

SWEEP_TOML = """title = "two stiffnesses"
sweep_file = "/nowhere/study.toml"
case = "/nowhere/case.toml"
mpile = "mpile"
python = "/nowhere/python"
threads = 1
parameters = ["materials.soil.young_modulus"]

[[gather]]
name = "kinetic_last"
series = "energy/kinetic"
reduce = "last"

[[gather]]
name = "{second}"
series = "energy/kinetic"
reduce = "max"

[[variants]]
id = "v01"
values = ["1.0e6"]
sets = ["materials.soil.young_modulus=1.0e6"]

[[variants]]
id = "v02"
values = ["2.0e6"]
sets = ["materials.soil.young_modulus=2.0e6"]
"""


def variant(directory, name, kinetic):
    """A finished variant whose kinetic energy goes 0, kinetic / 2, kinetic (J/rad)."""
    run = directory / "variants" / name
    run.mkdir(parents=True, exist_ok=True)
    write_history(run / "history.h5", {"/time": ([0.0, 1.0, 2.0], "s"),
                                       "/energy/kinetic": ([0.0, kinetic / 2, kinetic], "J/rad")})
    (run / "finished").touch()


def sweep_directory(directory, second="kinetic_max"):
    directory.mkdir(exist_ok=True)
    (directory / "sweep.toml").write_text(SWEEP_TOML.format(second=second))
    variant(directory, "v01", 10.0)
    variant(directory, "v02", 20.0)
    return directory


def results(directory):
    """{name: bytes} of the results and every other file of the directory's top level."""
    return {path.name: path.read_bytes() for path in directory.iterdir() if path.is_file()}


def test_failed_gathering_leaves_the_previous_results(tmp_path, monkeypatch):
    """A gathering that fails while writing results.nc (here: a full disk after part of the file)
    must leave the previous results.csv and results.nc byte for byte, and no temporary files;
    the next gathering that succeeds replaces them."""
    directory = sweep_directory(tmp_path / "sweep")
    sweep.gather(directory)
    before = results(directory)
    assert {"results.csv", "results.nc", "results.png", "sweep.toml"} == set(before)
    assert sweep.open_sweep(directory, form="pandas")["kinetic_last"].tolist() == [10.0, 20.0]

    variant(directory, "v02", 30.0)  # the new table differs from the old one

    class HalfWritten:
        def to_netcdf(self, path, **options):
            with open(path, "wb") as f:
                f.write(b"\x89HDF\r\n\x1a\n")
            raise OSError(28, "No space left on device")

    with monkeypatch.context() as patch:
        patch.setattr(sweep, "to_xarray", lambda *arguments: HalfWritten())
        with pytest.raises(OSError, match="No space left"):
            sweep.gather(directory)
    assert results(directory) == before

    sweep.gather(directory)
    assert pd.read_csv(directory / "results.csv")["kinetic_last"].tolist() == [10.0, 30.0]
    with xr.open_dataset(directory / "results.nc", engine="h5netcdf") as dataset:
        np.testing.assert_array_equal(dataset["kinetic_last"].values, [10.0, 30.0])
    assert set(results(directory)) == set(before)  # replaced, no temporary left beside them


@pytest.mark.parametrize("name, problem", [
    ("tip/F_y", "contains '/'"),
    ("kinetic max", "contains ' '"),
    (".kinetic", "starts with '.'"),
    ("status", "is a column already"),
    ("materials.soil.young_modulus", "is a column already"),
    ("kinetic_last", "is a column already"),
])
def test_gather_name_that_cannot_be_a_column_is_refused(tmp_path, name, problem):
    """The second [[gather]] entry's name cannot be a column of results.csv or a variable of
    results.nc: the gathering fails with the sweep file, the entry and the reason, before it
    writes anything (the previous results stay)."""
    directory = sweep_directory(tmp_path / "sweep")
    sweep.gather(directory)
    before = results(directory)
    (directory / "sweep.toml").write_text(SWEEP_TOML.format(second=name))
    with pytest.raises(RunFileError) as refused:
        sweep.gather(directory)
    assert str(refused.value).startswith(f"{directory / 'sweep.toml'}: [[gather]] number 2 (name = {name!r}): "
                                         f"the name {problem}")
    assert {k: v for k, v in results(directory).items() if k != "sweep.toml"} == \
        {k: v for k, v in before.items() if k != "sweep.toml"}


def test_a_series_in_no_history_is_refused_naming_the_nearest(tmp_path):
    """A misspelt series gave a column of NaN, as if no variant had reached it: a series that no
    readable history holds is refused, naming the entry and the nearest paths, before anything is
    written."""
    directory = sweep_directory(tmp_path / "sweep")
    text = (directory / "sweep.toml").read_text()
    (directory / "sweep.toml").write_text(text.replace('series = "energy/kinetic"\nreduce = "max"',
                                                       'series = "energy/kinetc"\nreduce = "max"'))
    with pytest.raises(RunFileError, match=r"\[\[gather\]\] number 2 \(name = 'kinetic_max'\): "
                       r"series 'energy/kinetc' is in no variant's history.h5; nearest: energy/kinetic"):
        sweep.gather(directory)
    assert not (directory / "results.csv").exists()
