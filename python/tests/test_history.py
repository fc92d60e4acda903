"""open_history: the series of history.h5 as an xarray Dataset and a pandas DataFrame."""
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest
from conftest import REPOSITORY, mpile_binary, write_history

import mpile
from mpile.files import RunFileError

# Values pass through h5py and xarray unchanged: compared exactly unless computed here.


def test_synthetic_run_values_names_units_and_attributes(synthetic_run):
    ds = mpile.open_history(synthetic_run)
    # 50 rows held, 501 installing, 0.01 s apart.
    assert ds.sizes["time"] == 551
    assert ds["time"].values[-1] == pytest.approx(5.5, abs=1e-12)  # 550 * 0.01 in floating point
    assert ds["time"].attrs["units"] == "s"
    # At 3 s into the installation (row 49 + 300): penetration 0.3 m, tip F_y = 50 kN/rad per 0.1 m.
    row = 349
    assert -ds["bodies/pile/u_y"].values[row] == pytest.approx(0.3, rel=1e-12)
    assert ds["reactions/pile/tip/F_y"].values[row] == pytest.approx(150e3, rel=1e-12)
    assert ds["reactions/pile/tip/F_y"].attrs["units"] == "N/rad"  # written as `unit` (older files)
    assert ds["reactions/pile/tip/M_theta"].attrs["units"] == "N m/rad"
    assert ds.attrs["title"] == "synthetic monopile"
    assert ds.attrs["status"] == "complete"
    # The synthetic file stores /phase as floats (as files did before it was an integer).
    assert ds["phase"].dtype == np.int64
    assert list(np.unique(ds["phase"].values)) == [0, 1]
    assert "phase" in ds.coords and "phase" not in ds.data_vars


def test_every_variable_has_units_and_matches_the_file(synthetic_run):
    ds = mpile.open_history(synthetic_run)
    with h5py.File(synthetic_run / "history.h5", "r") as raw:
        for name, variable in ds.data_vars.items():
            assert "units" in variable.attrs, name
            np.testing.assert_array_equal(variable.values, raw["/" + name][:])


def test_units_under_either_name_and_the_new_one_wins(tmp_path):
    for key in ("unit", "units"):
        path = write_history(tmp_path / f"{key}.h5", {"/time": ([0.0, 1.0], "s"),
                                                        "/energy/kinetic": ([0.0, 1.0], "J/m")}, units_key=key)
        assert mpile.open_history(path)["energy/kinetic"].attrs["units"] == "J/m"
    both = write_history(tmp_path / "both.h5", {"/time": ([0.0, 1.0], "s"), "/energy/kinetic": ([0.0, 1.0], "J/m")})
    with h5py.File(both, "a") as history:
        history["/energy/kinetic"].attrs["unit"] = "old"
    assert mpile.open_history(both)["energy/kinetic"].attrs["units"] == "J/m"


def test_pandas_and_xarray_forms_agree(synthetic_run, small_history):
    for path in (synthetic_run, small_history):
        ds = mpile.open_history(path)
        df = mpile.open_history(path, form="pandas")
        np.testing.assert_array_equal(df.index.values, ds["time"].values)
        assert df.index.name == "time"
        for name in ds.data_vars:
            np.testing.assert_array_equal(df[name].values, ds[name].values)
            assert df.attrs["units"][name] == ds[name].attrs["units"]
        for name in ("step", "phase"):
            if name in ds.coords:
                np.testing.assert_array_equal(df[name].values, ds[name].values)
        assert set(df.columns) == set(ds.data_vars) | ({"step", "phase"} & set(ds.coords))
        assert df.attrs["title"] == ds.attrs["title"]


def test_small_history_known_values(small_history):
    ds = mpile.open_history(small_history.parent)  # the run directory
    assert list(ds["step"].values) == [0, 10, 20]
    assert list(ds["phase"].values) == [0, 1, 1]
    assert list(ds["reactions/pile/tip/F_y"].sel(time=0.5, method="nearest").values.ravel()) == [100.0]
    assert ds.attrs["threads"] == 2.0
    assert isinstance(ds.attrs["title"], str)


def test_refuses_missing_and_foreign_files(tmp_path):
    with pytest.raises(RunFileError, match="nothere"):
        mpile.open_history(tmp_path / "nothere")
    with pytest.raises(RunFileError, match=f"{tmp_path}.*holds no history.h5"):
        mpile.open_history(tmp_path)
    text = tmp_path / "notes.txt"
    text.write_text("not HDF5\n")
    with pytest.raises(RunFileError, match="notes.txt is not a readable HDF5 file"):
        mpile.open_history(text)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["values"] = np.arange(3.0)
    with pytest.raises(RunFileError, match="other.h5 is not an mpile history"):
        mpile.open_history(other)
    with pytest.raises(ValueError, match="form"):
        mpile.open_history(other, form="csv")


def test_unequal_series_cut_while_running_refused_when_complete(tmp_path):
    series = {"/time": ([0.0, 1.0, 2.0], "s"), "/energy/kinetic": ([5.0, 6.0], "J/m")}
    running = write_history(tmp_path / "running.h5", series, attrs={"status": "running"})
    ds = mpile.open_history(running)
    assert ds.sizes["time"] == 2 and list(ds["energy/kinetic"].values) == [5.0, 6.0]
    complete = write_history(tmp_path / "complete.h5", series, attrs={"status": "complete"})
    with pytest.raises(RunFileError, match="energy/kinetic: 2 values, time: 3"):
        mpile.open_history(complete)


def test_reads_while_a_writer_holds_the_file_open(synthetic_run, tmp_path):
    """A run keeps its history open for writing with HDF5's lock; reading must neither wait nor fail."""
    path = tmp_path / "history.h5"
    path.write_bytes((synthetic_run / "history.h5").read_bytes())
    writer = subprocess.Popen([sys.executable, "-c",
                               "import h5py, sys, time\n"
                               f"f = h5py.File({str(path)!r}, 'a')\n"
                               "print('open', flush=True)\n"
                               "sys.stdin.read()\n"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert writer.stdout.readline().strip() == "open"
        started = time.monotonic()
        assert mpile.open_history(path).sizes["time"] == 551
        assert time.monotonic() - started < 10.0  # reading 551 rows takes milliseconds; a wait would not end
    finally:
        writer.stdin.close()
        writer.wait(timeout=30)


def test_a_restarted_run_reads_as_running_until_it_stops(tmp_path):
    """A restart reopens the history its first part closed as interrupted: while it runs, a reader
    (tools/convergence.py --running, a sweep's table) must see it running, not finished."""
    binary = mpile_binary()
    if binary is None:
        pytest.skip("no mpile program: set MPILE to its path (ctest does)")
    case = REPOSITORY / "cases" / "verification" / "v7_block_on_incline.toml"
    out = tmp_path / "run"
    # Without gravity the block rests, so a long phase neither ends nor fails while it is read.
    run = [binary, "run", str(case), "--out", str(out), "--threads", "1",
           "--set", "solver.gravity=[0.0, 0.0]", "--set", "phases.0.duration=1000"]
    first = subprocess.run(run + ["--stop-after", "20"], capture_output=True, timeout=120)
    assert first.returncode == 130, first.stderr
    interrupted = mpile.open_history(out)
    assert interrupted.attrs["status"].startswith("interrupted at")
    rows = interrupted.sizes["time"]
    second = subprocess.Popen(run + ["--restart", str(out / "checkpoint.h5")],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        seen = None
        deadline = time.monotonic() + 60.0  # rows are written every 2 s
        while seen is None and time.monotonic() < deadline and second.poll() is None:
            time.sleep(0.2)
            try:
                ds = mpile.open_history(out)
            except (OSError, RunFileError):
                continue  # caught between the writer's open and close: read again
            if ds.sizes["time"] > rows:
                seen = ds.attrs["status"]
        assert seen == "running"
    finally:
        second.terminate()
        second.wait(timeout=60)
    assert mpile.open_history(out).attrs["status"].startswith("interrupted at")


def test_real_run(real_run):
    ds = mpile.open_history(real_run)
    assert ds.attrs["status"] == "complete"
    assert ds["time"].values[-1] == pytest.approx(1.0, abs=1e-9)  # the phase lasts exactly 1 s
    steps = ds["step"].values
    assert steps.dtype.kind == "i" and np.all(np.diff(steps) > 0)
    assert list(np.unique(ds["phase"].values)) == [0]
    slope = ds["reactions/incline/slope/F_y"]
    assert slope.attrs["units"] == "N/m"
    assert slope.attrs["plan_area"] == pytest.approx(5.0)  # the incline's top, 5 m wide
    # The block (1 m x 0.5 m, 1000 kg/m^3) rests on the incline: over the last half second the
    # normal force on the slope averages its weight's normal part 500 kg/m * 8.49571 m/s^2 within
    # 2 % (the elastic block's oscillation about it). The force of one step swings from 0 to three
    # times the weight, so the mean is taken over every step, weighted by its dt (a mean of rows
    # 0.01 s apart was 2 to 4 % off by where the rows fell).
    late = ds["time"].values > 0.5
    dt = ds["dt"].values[late]
    mean = float(np.sum(slope.values[late] * dt) / np.sum(dt))
    assert abs(mean) == pytest.approx(500.0 * 8.49571, rel=0.02)
    with h5py.File(real_run / "history.h5", "r") as raw:
        for name in ("energy/kinetic", "bodies/incline/u_y", "reactions/incline/slope/F_r"):
            np.testing.assert_array_equal(ds[name].values, raw[name][:])


def test_data_damaged_on_disk_is_refused_not_read_back_as_other_numbers(real_run, tmp_path):
    # mpile writes a Fletcher32 checksum on every chunk: one flipped byte in /energy/kinetic's data
    # makes the read fail, and the package says so with its own error. Without the checksums the
    # series read back with one value changed and no word.
    damaged = tmp_path / "history.h5"
    shutil.copyfile(real_run / "history.h5", damaged)
    with h5py.File(damaged, "r") as raw:
        kinetic = raw["energy/kinetic"]
        assert kinetic.fletcher32
        offset = kinetic.id.get_chunk_info(0).byte_offset
    with open(damaged, "r+b") as raw:
        raw.seek(offset + 8 * 20 + 3)
        byte = raw.read(1)
        raw.seek(offset + 8 * 20 + 3)
        raw.write(bytes([byte[0] ^ 0xFF]))
    with pytest.raises(mpile.RunFileError, match="damaged data, it cannot be read"):
        mpile.open_history(damaged)
    with pytest.raises(mpile.RunFileError, match="damaged data"):
        mpile.read_series(damaged, ["/energy/kinetic", "/time"])
    assert len(mpile.read_series(damaged, ["/time"])["/time"]) > 20  # the rest reads as before


def test_xarray_alone_reads_a_group_on_the_shared_time(real_run):
    # The root of history.h5 holds time, step, dt, phase and wall_time; each group's series are
    # read with group=... (docs/case-format.md says so), on the one dimension time, equal to what
    # mpile.open_history gathers from every group.
    xarray = pytest.importorskip("xarray")
    with xarray.open_dataset(real_run / "history.h5", engine="h5netcdf") as root:
        assert set(root.variables) == {"time", "step", "dt", "phase", "wall_time"}
    with xarray.open_dataset(real_run / "history.h5", engine="h5netcdf", group="energy") as energy:
        assert energy["kinetic"].dims == ("time",)
        kinetic = energy["kinetic"].values
    np.testing.assert_array_equal(kinetic, mpile.open_history(real_run)["energy/kinetic"].values)
