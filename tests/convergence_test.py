#!/usr/bin/python3
"""tools/convergence.py on values whose limit and order are known exactly.

f(h) = f0 + C h^p with p = 1.5 at three unevenly refined cell sizes must give p and f0 to the
bisection's precision (1e-9 relative: 200 halvings leave far less, round-off remains); values
that oscillate with refinement must be reported as having no observed order, their value the
finest run's with half the range as its band. End to end, three
synthetic histories with such forces must be read at a penetration and extrapolated the same way,
the body's whole axial force (total_Fy) and tip plus inner wall (base_Fy) likewise, and an
ensemble of three runs at the finest resolution, offset by -0.3, 0 and +0.3, must give the same
limit with a scatter of exactly 0.3 (their standard deviation, n - 1) and the sum of their wall
times.
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import convergence  # noqa: E402

H = [0.004, 0.0053, 0.008]  # finest first, ratios 1.33 and 1.51
F0, C, P = 12.5, -300.0, 1.5


def exact(h):
    return F0 + C * h**P


def check(name, ok):
    print(f"{name}: {'ok' if ok else 'FAILED'}")
    return ok


def write_history(path, h, wall, status="complete", offset=0.0, monopile="", torn=False):
    """A history of 101 rows; `torn` gives the tip's series one row more, as a running writer
    leaves it between extending one series and the next."""
    rows = 101
    with h5py.File(path, "w") as f:
        f.attrs["status"] = status
        if status != "running":  # written when a run ends
            f.attrs["wall_time"] = wall
        f.attrs["case_text"] = monopile + '[[phases]]\nname = "a"\n[[phases]]\nname = "b"\n'
        f["/time"] = np.linspace(0.0, 1.0, rows)
        f["/phase"] = np.r_[np.zeros(1), np.ones(rows - 1)]
        f["/bodies/pile/u_y"] = -np.linspace(0.0, 0.1, rows)
        # A force that does not vary with depth, so the window's mean is the value itself.
        f["/reactions/pile/tip/F_y"] = np.full(rows + int(torn), (exact(h) + offset) * 1e3)
        # The body's whole axial force: twice the tip's, so its limit is 2 F0 at the same order.
        f["/bodies/pile/contact_F_y"] = np.full(rows, 2.0 * (exact(h) + offset) * 1e3)
        # The inner wall: three times the tip's plus 1, so tip plus inner wall has the limit
        # 4 F0 + 1 at the same order (and is told apart from the tip or the inner wall alone).
        f["/reactions/pile/internal_shaft/F_y"] = np.full(rows, (3.0 * (exact(h) + offset) + 1.0) * 1e3)


def check_sweep():
    """A resolution sweep's output read by --sweep: each variant's h is wall_thickness /
    wall_cells from the case it ran (0.0159 / 2, 3 and 4: ratios 1.5 and 1.33), two variants at one wall_cells are an ensemble, a variant without a history stops the
    tool unless --running, and a sweep that does not finish is reported, not read."""
    ok = True
    tool = [sys.executable, os.path.join(ROOT, "tools", "convergence.py")]
    with tempfile.TemporaryDirectory() as directory:
        variants = [("v01", 4, -0.3), ("v02", 3, 0.0), ("v03", 2, 0.0), ("v04", 4, 0.3),
                    ("v05", 1, 0.0)]
        with open(os.path.join(directory, "sweep.toml"), "w") as f:
            for name, cells, _ in variants:
                f.write(f'[[variants]]\nid = "{name}"\nvalues = ["{cells}"]\nsets = []\n')
        for name, cells, offset in variants[:4]:  # v05 has not run yet
            run = os.path.join(directory, "variants", name)
            os.makedirs(run)
            write_history(os.path.join(run, "history.h5"), 0.0159 / cells, 10.0, offset=offset,
                          monopile=f"[monopile]\nwall_thickness = 0.0159\nwall_cells = {cells}\n")
        refused = subprocess.run(tool + ["--sweep", directory, "--at", "0.05",
                                         "--quantities", "tip_Fy"], capture_output=True, text=True)
        ok &= check("a variant without a history stops the sweep's study",
                    refused.returncode != 0 and "variant v05 has no history" in refused.stderr)
        read = subprocess.run(tool + ["--sweep", directory, "--at", "0.05", "--quantities",
                                      "tip_Fy", "--running"], capture_output=True, text=True)
        print(read.stdout, read.stderr)
        ok &= check("the sweep's cell sizes are the wall's thickness over its cells",
                    read.returncode == 0 and "h=0.003975  h=0.0053  h=0.00795" in read.stdout)
        # The exact f0 + C h^1.5 at the three wall resolutions, the four-cell pair's mean exact.
        ok &= check("the sweep is extrapolated to the known limit and order",
                    "1.50  12.5 +-" in read.stdout)
        # Members offset by -0.3 and +0.3: standard deviation (n - 1) 0.3 sqrt(2) = 0.42.
        ok &= check("two variants at one wall resolution are an ensemble (wall time 10 + 10 s)",
                    "h=0.003975: 20" in read.stdout and "  0.42  (the finest" in read.stdout)
        failed = subprocess.run(tool + ["--sweep", os.path.join(directory, "study.toml"),
                                        "--out", directory, "--mpile", "/bin/false", "--at",
                                        "0.05"], capture_output=True, text=True)
        ok &= check("a sweep that does not finish is reported, not read",
                    failed.returncode != 0 and "did not finish" in failed.stderr)
    return ok


def main():
    ok = True
    f = [exact(h) for h in H]
    p = convergence.observed_order(H, f)
    ok &= check("order of f0 + C h^1.5", p is not None and abs(p - P) < 1e-9)
    f0, band, _, observed = convergence.extrapolate(H, f, 1.0)
    ok &= check("extrapolated limit", observed and abs(f0 - F0) < 1e-9 * F0)
    # The band is 1.25 times the Richardson correction, which here is the exact error.
    ok &= check("error band", abs(band - 1.25 * abs(f[0] - F0)) < 1e-9 * abs(f[0] - F0))
    wobble = [F0 + 0.1, F0 - 0.2, F0 + 0.4]
    ok &= check("oscillation has no order", convergence.observed_order(H, wobble) is None)
    # Oscillating, the finest value stands, +- half the three's range: (0.4 - -0.2) / 2 = 0.3 (the
    # fallback's Richardson would have given f0 - 0.3 / 0.325 = 11.68 +- 2.8, past every value).
    f02, band2, p2, observed2 = convergence.extrapolate(H, wobble, 1.0)
    ok &= check("oscillation: the finest value +- half the range",
                not observed2 and np.isnan(p2) and f02 == wobble[0] and abs(band2 - 0.3) < 1e-12)
    # Monotone, but converging faster than h^4 (no order in range): the assumed order, safety 3.
    steep = [F0, F0 + 0.01, F0 + 1.0]
    ok &= check("monotone without an order in range has none",
                convergence.observed_order(H, steep) is None)
    f03, band3, p3, observed3 = convergence.extrapolate(H, steep, 1.0)
    ratio = H[1] / H[0] - 1.0
    ok &= check("and falls back to the assumed order and safety 3",
                not observed3 and p3 == 1.0 and abs(f03 - (F0 - 0.01 / ratio)) < 1e-12
                and abs(band3 - 3.0 * 0.01 / ratio) < 1e-12)
    with tempfile.TemporaryDirectory() as directory:
        specs = []
        for k, h in enumerate(H):
            run = os.path.join(directory, f"run{k}")
            os.makedirs(run)
            write_history(os.path.join(run, "history.h5"), h, 10.0 * (k + 1))
            specs.append(f"{run}:{h}")
        out = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "convergence.py"), *specs,
                              "--at", "0.05", "--quantities", "tip_Fy",
                              "--csv", os.path.join(directory, "t.csv")],
                             capture_output=True, text=True)
        print(out.stdout, out.stderr)
        ok &= check("tool exit status", out.returncode == 0)
        ok &= check("tool prints order and limit", "1.50  12.5 +-" in out.stdout)
        total = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "convergence.py"),
                                *specs, "--at", "0.05", "--quantities", "total_Fy"],
                               capture_output=True, text=True)
        ok &= check("the body's whole axial force is read from its contact_F_y",
                    total.returncode == 0 and "total_Fy" in total.stdout
                    and "1.50  25 +-" in total.stdout)
        base = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "convergence.py"),
                               *specs, "--at", "0.05", "--quantities", "base_Fy"],
                              capture_output=True, text=True)
        ok &= check("tip plus inner wall is the sum of their F_y",
                    base.returncode == 0 and "1.50  51 +-" in base.stdout)
        # An ensemble at the finest resolution: the members' mean is the exact value, their
        # standard deviation 0.3, their cost the sum of their wall times (10 + 11 + 12 s).
        members = []
        for k, offset in enumerate((-0.3, 0.0, 0.3)):
            run = os.path.join(directory, f"member{k}")
            os.makedirs(run)
            write_history(os.path.join(run, "history.h5"), H[0], 10.0 + k, offset=offset)
            members.append(run)
        ensemble = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "convergence.py"),
                                   "+".join(members) + f":{H[0]}", *specs[1:], "--at", "0.05",
                                   "--quantities", "tip_Fy"], capture_output=True, text=True)
        print(ensemble.stdout, ensemble.stderr)
        ok &= check("an ensemble's mean is extrapolated as one run's value",
                    ensemble.returncode == 0 and "1.50  12.5 +-" in ensemble.stdout)
        # 0.3 exceeds the finest two's difference (0.04), so the table says the extrapolation
        # rests on noise.
        ok &= check("an ensemble's scatter is its members' standard deviation",
                    "  0.3  (the finest two differ by less than it)" in ensemble.stdout)
        ok &= check("an ensemble's wall time is its members' sum",
                    f"h={H[0]:g}: 33" in ensemble.stdout)
        # Values that oscillate (no order) with the finest two 0.3 apart, less than the finest
        # ensemble's scatter of 0.42: the finest value itself, 12.6, +- that scatter, not an
        # extrapolation of the noise (which would give 12.6 + 0.3 / 0.325 = 13.5).
        noisy = []
        for k, offset in enumerate((-0.3, 0.3)):
            run = os.path.join(directory, f"noisy{k}")
            os.makedirs(run)
            write_history(os.path.join(run, "history.h5"), H[0], 10.0,
                          offset=F0 + 0.1 - exact(H[0]) + offset)
            noisy.append(run)
        for k, value in ((1, F0 - 0.2), (2, F0 + 0.4)):
            run = os.path.join(directory, f"noisy{k + 1}")
            os.makedirs(run)
            write_history(os.path.join(run, "history.h5"), H[k], 10.0, offset=value - exact(H[k]))
            noisy.append(run)
        within = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "convergence.py"),
                                 "+".join(noisy[:2]) + f":{H[0]}", f"{noisy[2]}:{H[1]}",
                                 f"{noisy[3]}:{H[2]}", "--at", "0.05", "--quantities", "tip_Fy"],
                                capture_output=True, text=True)
        print(within.stdout, within.stderr)
        ok &= check("no order and the finest two within the scatter: the finest value +- scatter",
                    within.returncode == 0 and "12.6 +- 0.42" in within.stdout)
        # A run still going (it reached 0.1 m): refused unless --running, and then read only at
        # depths it has passed.
        write_history(os.path.join(directory, "run0", "history.h5"), H[0], 10.0, "running")
        tool = [sys.executable, os.path.join(ROOT, "tools", "convergence.py"), *specs,
                "--quantities", "tip_Fy"]
        refused = subprocess.run(tool + ["--at", "0.05"], capture_output=True, text=True)
        ok &= check("a running run is refused", refused.returncode != 0
                    and "is not a complete run" in refused.stderr)
        read = subprocess.run(tool + ["--at", "0.05", "--running"], capture_output=True, text=True)
        ok &= check("--running reads it where it has passed",
                    read.returncode == 0 and "1.50  12.5 +-" in read.stdout)
        write_history(os.path.join(directory, "run0", "history.h5"), H[0], 10.0, "running",
                      torn=True)
        torn = subprocess.run(tool + ["--at", "0.05", "--running"], capture_output=True, text=True)
        ok &= check("--running reads a history caught between two series' rows",
                    torn.returncode == 0 and "1.50  12.5 +-" in torn.stdout)
        ahead = subprocess.run(tool + ["--at", "0.095", "--running"], capture_output=True, text=True)
        ok &= check("--running refuses a depth not passed yet", ahead.returncode != 0
                    and "has not passed" in ahead.stderr)
    ok &= check_sweep()
    print("all ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
