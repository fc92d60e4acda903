#!/usr/bin/python3
"""history.h5 read while its run appends to it, the way a researcher follows a run from Python.

  read_history_while_running.py MPILE CASE OUT

Starts `mpile run CASE --out OUT` and, until it ends, opens OUT/history.h5 with h5py's default
settings (HDF5 file locking on), reads /time, keeps the file open for a while and closes it. The run
must end complete, and the reader must have seen the history grow at least three times while the
run went on, with every row it saw equal to the final file's. Then xarray must open the finished
file (h5netcdf engine) with /time as the dimension of the root's series and of a body's group.
Prints two lines and exits 0 on success, 1 otherwise.
"""
import subprocess
import sys
import time

import h5py
import numpy as np


def main():
    mpile, case, out = sys.argv[1:4]
    # The history is flushed every 2 s of wall time: the run must last several of those for the
    # reader to see it grow three times. V9's one second of spin took 5 to 6 s on a quiet 2-core
    # machine and the reader then saw two lengths; four seconds of it take about 20 s.
    run = subprocess.Popen([mpile, "run", case, "--out", out, "--threads", "1",
                            "--set", "phases.spin.duration=4.0"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seen = []  # the /time arrays read while the run went on
    failures = []
    while run.poll() is None:
        try:
            with h5py.File(f"{out}/history.h5", "r") as history:
                seen.append(history["/time"][()])
                # A reader that holds the file open (a notebook, HDFView) must not stop the run.
                time.sleep(0.7)
        except (OSError, KeyError) as error:
            # Before the run creates the file, or while a flush rewrites its metadata.
            failures.append(str(error))
            time.sleep(0.1)
    stderr = run.communicate()[1]
    with h5py.File(f"{out}/history.h5", "r") as history:
        status = history.attrs["status"]
        final = history["/time"][()]
    growth = len({len(t) for t in seen if len(t) > 0})
    consistent = all(np.array_equal(t, final[: len(t)]) for t in seen)
    print(f"exit {run.returncode}, status {status}, {len(seen)} reads, {growth} distinct lengths, "
          f"{len(failures)} failed opens, rows consistent: {consistent}")
    ok = run.returncode == 0 and status == "complete" and growth >= 3 and consistent
    if not ok:
        print(stderr, failures[:3], file=sys.stderr)
    return 0 if ok and shares_time_dimension(f"{out}/history.h5", len(final)) else 1


def shares_time_dimension(path, rows):
    import xarray

    root = xarray.open_dataset(path, engine="h5netcdf")
    pile = xarray.open_dataset(path, engine="h5netcdf", group="bodies/pile")
    dims = {name: root[name].dims for name in ("step", "phase", "dt")}
    dims["bodies/pile/penetration"] = pile["penetration"].dims
    ok = all(d == ("time",) for d in dims.values()) and root.sizes["time"] == rows
    ok &= pile.sizes["time"] == rows and root["time"].attrs["units"] == "s"
    print(f"xarray: time dimension of {rows} rows shared by {', '.join(dims)}: {ok}")
    return ok


if __name__ == "__main__":
    sys.exit(main())
