#!/usr/bin/python3
"""`mpile sweep` of values that carry code (tests/data/sweeps/hostile.toml): shell quotes,
command substitution, Snakemake's braces, Python, newlines and a rule. Each variant must run and
record its value as the plain text it is (the history's title), and no file the code would create
may appear in the sweep's directory or the directory the sweep ran from.

  hostile_sweep.py MPILE SWEEP_FILE WORK_DIRECTORY
"""
import glob
import os
import shutil
import subprocess
import sys
import tomllib

import h5py

mpile_binary, sweep_file, work = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
out = os.path.join(work, "sweep")
with open(sweep_file, "rb") as f:
    values = tomllib.load(f)["parameters"]["title"]

done = subprocess.run([mpile_binary, "sweep", sweep_file, "--out", out,
                       "--cores", "2"], capture_output=True, text=True, timeout=300, cwd=work)
failures = []
if done.returncode != 0:
    failures.append(f"exit status {done.returncode}: {done.stderr[-600:]}")
for k, value in enumerate(values, 1):
    history = os.path.join(out, "variants", f"v{k:02d}", "history.h5")
    if not os.path.exists(history):
        failures.append(f"v{k:02d} wrote no history")
        continue
    with h5py.File(history, "r") as h:
        title = h.attrs["title"]
        title = title.decode() if isinstance(title, bytes) else str(title)
    if title != value:
        failures.append(f"v{k:02d}: the run's title is {title!r}, its value {value!r}")
planted = glob.glob(os.path.join(work, "**", "PWNED*"), recursive=True)
if planted:
    failures.append(f"code in a value ran: {planted}")
for failure in failures:
    print("FAIL", failure)
print(f"{len(values)} values carrying code: " + ("all ran as plain text" if not failures else
                                                 f"{len(failures)} failures"))
sys.exit(1 if failures else 0)
