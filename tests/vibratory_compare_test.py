#!/usr/bin/python3
"""tools/vibratory_compare.py on synthetic histories whose answers are known exactly: a pile that
sinks at a constant rate while it oscillates at the drive's frequency, after a phase that drove it
elsewhere, and two monitors, one near PPT A with a known pore pressure.

    /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/vibratory_compare_test.py

Python alone, about a second. What must come out: the cycle mean of a sine over whole cycles
vanishes, so each row is the linear trend at its time, counted from the vibration phase's start
(the earlier phase's penetration left out); the last window moves back to end at the last row;
the frequency comes from the phase's harmonic force_y in case_resolved; the monitor is the one that
started nearest PPT A; its pore pressure is printed compression positive per 0.5 s window.
"""
import math
import pathlib
import sys

import h5py
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import vibratory_compare as vc  # noqa: E402

FREQUENCY = 25.0
START = 0.3          # s: the vibration phase's start
BEFORE = 0.15        # m: the penetration reached before it (jacked)
RATE = 0.058         # m/s: the synthetic sinking during vibration
AMPLITUDE = 1.5e-3   # m: the oscillation about it

CASE = f"""
[[phases]]
name = "jacking"
duration = 0.5

[[phases]]
name = "vibration"
duration = 3.0
drive = {{ body = "pile", force_y = {{ type = "harmonic", amplitude = 41.9, frequency = {FREQUENCY} }} }}
"""


def pore(t):
    """The monitor's pore pressure, tension positive as written (Pa): 3 kPa of compression with a
    1.5 kPa swing whose amplitude falls from 1 to 0 over the 3 s."""
    return -(3.0e3 + 1.5e3 * (1.0 - t / 3.0) * np.sin(2 * np.pi * FREQUENCY * t))


def tip_force(t):
    """The soil's upward force on the tip (N/rad) and the pore pressure's part of it: 24 N/rad with
    a swing of 30 whose mean over each 0.5 s window (12.5 cycles, a cosine: its integral ends where
    sin vanishes) is zero, the water's part a quarter of it before 1 s of vibration and three
    quarters after."""
    total = 24.0 + 30.0 * np.cos(2 * np.pi * FREQUENCY * t)
    return total, np.where(t < 1.0, 0.25, 0.75) * total


def write_history(path, end=START + 3.0, interval=1e-3, case=CASE, rate=RATE, tip=True):
    """Rows every `interval` to `end`, the phase boundary a row of its own, as the engine writes."""
    time = np.unique(np.concatenate((np.arange(0.0, end + 0.5 * interval, interval), [START])))
    t = time - START
    penetration = np.where(t < 0.0, BEFORE * time / START,
                           BEFORE + rate * t + AMPLITUDE * np.sin(2 * np.pi * FREQUENCY * t))
    with h5py.File(path, "w") as f:
        f.attrs["case_resolved"] = case
        f.attrs["title"] = "synthetic vibratory run"
        f.attrs["status"] = "complete"
        f.attrs["threads"] = 1
        f.attrs["wall_time"] = 12.0
        f["time"] = time
        for index, (name, start) in enumerate((("jacking", 0.0), ("vibration", START))):
            g = f.create_group(f"phases/{index}")
            g.attrs["name"] = name
            g.attrs["start"] = start
        f["bodies/pile/penetration"] = penetration
        if tip:
            total, water = tip_force(t)
            f["reactions/pile/tip/F_y"] = total
            f["reactions/pile/tip/pore_F_y"] = water
        for name, (r, y), pressure in (("far", (0.2, 0.3), np.zeros_like(time)),
                                       ("ppt_a", (0.036, 0.621), np.where(t < 0, -3e3, pore(t)))):
            g = f.create_group(f"monitors/{name}")
            g["r"] = np.full_like(time, r)
            g["y"] = np.full_like(time, y)
            g["pore_pressure"] = pressure
    return path


def test_cycle_mean_of_a_trend_and_sine_is_the_trend_at_the_centre():
    """Over one whole period the sine's trapezoid sums to zero for any sampling that has both
    window ends (interpolated) and the rows between; the linear part is exact."""
    time = np.linspace(0.0, 1.0, 1001)
    values = 2.0 + 3.0 * time + 0.7 * np.sin(2 * np.pi * 25.0 * time + 0.3)
    for centre in (0.25, 0.5137, 0.98):
        mean, at = vc.cycle_mean(time, values, centre, 0.04)
        assert at == pytest.approx(centre)
        # The sine's remainder: interpolating its ends linearly costs O((2 pi f dt)^2) of it.
        assert mean == pytest.approx(2.0 + 3.0 * centre, abs=0.7 * (2 * np.pi * 25e-3) ** 2)


def test_cycle_mean_moves_a_window_past_the_end_back_and_refuses_one_before_the_start():
    time = np.linspace(0.0, 1.0, 1001)
    values = 3.0 * time
    mean, at = vc.cycle_mean(time, values, 1.0, 0.04)
    assert at == pytest.approx(0.98)
    assert mean == pytest.approx(3.0 * 0.98)
    with pytest.raises(ValueError):
        vc.cycle_mean(time, values, 0.01, 0.04)


def test_reads_the_vibration_phase_and_counts_from_its_start(tmp_path):
    run = vc.read_run(write_history(tmp_path / "history.h5"), "vibration")
    assert run["body"] == "pile"
    assert run["start"] == pytest.approx(START)
    assert run["start_penetration"] == pytest.approx(BEFORE)
    assert run["time"][0] == pytest.approx(0.0)
    assert run["time"][-1] == pytest.approx(3.0)
    assert vc.drive_frequency(run["case"], "vibration") == FREQUENCY
    assert vc.drive_frequency(run["case"], "jacking") is None


def test_rows_are_the_trend_at_each_time(tmp_path):
    run = vc.read_run(write_history(tmp_path / "history.h5"), "vibration")
    rows = vc.penetration_rows(run, 1.0 / FREQUENCY)
    assert [r[0] for r in rows] == list(vc.TIMES)
    for t, cycles, mm, centre in rows:
        assert cycles == pytest.approx(t * FREQUENCY)
        expected_centre = min(t, 3.0 - 0.02)          # the last window ends at the last row
        assert centre == pytest.approx(expected_centre)
        assert mm == pytest.approx(1e3 * RATE * expected_centre, abs=0.02)


def test_a_short_run_leaves_the_times_it_did_not_reach_empty(tmp_path):
    run = vc.read_run(write_history(tmp_path / "history.h5", end=START + 1.1), "vibration")
    rows = {t: (mm, centre) for t, _, mm, centre in vc.penetration_rows(run, 1.0 / FREQUENCY)}
    assert rows[1.0][0] == pytest.approx(1e3 * RATE * 1.0, abs=0.02)
    assert rows[1.25] == (None, None)
    assert rows[3.0] == (None, None)


def test_the_monitor_nearest_ppt_a_and_its_pore_pressure_compression_positive(tmp_path):
    run = vc.read_run(write_history(tmp_path / "history.h5"), "vibration")
    assert vc.nearest_monitor(run["monitors"], vc.PPT_A) == "ppt_a"
    assert vc.nearest_monitor(run["monitors"], (0.21, 0.3)) == "far"
    rows = vc.pore_rows(run["time"], run["monitors"]["ppt_a"][1])
    assert [w for w, _, _, _ in rows] == list(vc.PPT_WINDOWS)
    # The first window by hand: its first crest is a quarter cycle in (t = 0.01 s), its first
    # trough three quarters (0.03 s), both on rows (every 1 ms from the phase's start).
    assert rows[0][2] == pytest.approx(3.0 + 1.5 * (1.0 - 0.01 / 3.0), abs=1e-9)
    assert rows[0][1] == pytest.approx(3.0 - 1.5 * (1.0 - 0.03 / 3.0), abs=1e-9)
    # Every window against the rows' own extremes in it, compression positive.
    omega = 2 * np.pi * FREQUENCY

    def integral(t):  # of 1.5 (1 - t / 3) sin(omega t), kPa s: by parts
        return 1.5 * (-(1.0 - t / 3.0) * np.cos(omega * t) / omega
                      - np.sin(omega * t) / (3.0 * omega**2))

    for (a, b), low, high, mean in rows:
        t = np.arange(round(a * 1e3), round(b * 1e3) + 1) * 1e-3
        assert high == pytest.approx(np.max(-pore(t)) / 1e3, abs=1e-6)
        assert low == pytest.approx(np.min(-pore(t)) / 1e3, abs=1e-6)
        # The closed-form mean over the window; the trapezoid rule on 1 ms rows (40 a cycle) is
        # within (b - a) h^2 / 12 max|u''| / (b - a) = 1e-6 / 12 x 1.5 omega^2 = 3.1e-3 kPa of it.
        assert mean == pytest.approx(3.0 + (integral(b) - integral(a)) / (b - a), abs=3.1e-3)


def test_main_prints_the_table_beside_the_measured_column(tmp_path, capsys):
    write_history(tmp_path / "history.h5")
    assert vc.main([str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "| 0.50 | 12 | 29.0 | 21.4 | 32.8 | 1.36 |" in out
    assert "| 3.00 | 75 | 172.8 (2.980 s) | 174.5 | 168.5 | 0.99 |" in out
    assert "monitor 'ppt_a'" in out
    assert "| 0-0.5 | 1.5 / 4.5 | 3.0 | 1.6 / 4.8 | 1.2 / 4.8 |" in out


def test_what_carries_the_tip_per_window(tmp_path, capsys):
    """Each 0.5 s window: the trend's rate per cycle (the sine is zero at the windows' ends, so the
    rate is RATE / FREQUENCY exactly), the tip force's mean (the trapezoid rule integrates the
    cosine exactly there: every odd derivative vanishes at both ends) and the water's share of it,
    a quarter, then three quarters from 1 s. The window 0.5-1 s ends on the step: its last row
    (54 N/rad) takes the later share over half of a 1 ms interval, 0.5 x 1e-3 x 0.5 x 54 / (0.5 x
    24) = 1.125e-3 more share."""
    run = vc.read_run(write_history(tmp_path / "history.h5"), "vibration")
    rows = vc.tip_rows(run, 1.0 / FREQUENCY)
    assert [w for w, _, _, _ in rows] == list(vc.PPT_WINDOWS)
    for (a, b), rate, total, share in rows:
        assert rate == pytest.approx(1e3 * RATE / FREQUENCY, abs=1e-9)
        assert total == pytest.approx(24.0, abs=1e-9)
        expected = 0.25 if b < 1.0 else 0.25 + 1.125e-3 if b == 1.0 else 0.75
        assert share == pytest.approx(expected, abs=1e-9)
    assert vc.main([str(tmp_path)]) == 0
    assert "| 1.5-2 | 2.32 | 24.0 | 75 % |" in capsys.readouterr().out
    # Without the tip's record the rate is still there and the forces are not.
    run = vc.read_run(write_history(tmp_path / "bare.h5", tip=False), "vibration")
    assert [row[2:] for row in vc.tip_rows(run, 1.0 / FREQUENCY)] == [(None, None)] * 6


def test_expect_passes_within_its_band_and_fails_outside_it_or_short(tmp_path, capsys):
    # The synthetic run sinks 29.0 mm by 0.5 s against the measured 21.4: 1.36 times it.
    write_history(tmp_path / "history.h5")
    assert vc.main([str(tmp_path), "--expect", "0.5=0.36"]) == 0
    assert "vibratory check: ok" in capsys.readouterr().out
    assert vc.main([str(tmp_path), "--expect", "0.5=0.35"]) == 1
    assert "vibratory check: FAILED: at 0.5 s 29.0 mm" in capsys.readouterr().out
    write_history(tmp_path / "short.h5", end=START + 0.4)
    assert vc.main([str(tmp_path / "short.h5"), "--expect", "0.5=1.0"]) == 1
    assert "at 0.5 s - mm" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        vc.main([str(tmp_path), "--expect", "0.4=0.1"])


def test_the_measured_numbers_are_the_pages(tmp_path):
    """The tool's columns are docs/vibratory-model-test.md section 3's: each measured and CEL
    penetration and each PPT A window appears in the page's tables."""
    page = (ROOT / "docs" / "vibratory-model-test.md").read_text()
    for t, mm in vc.MEASURED_MM.items():
        row = [line for line in page.splitlines() if line.startswith(f"| {t:.2f} | ")]
        assert row, t
        cells = [c.strip() for c in row[0].split("|")[1:-1]]
        assert float(cells[2]) == mm and float(cells[3]) == vc.CEL_MM[t]
    measured = next(line for line in page.splitlines() if line.startswith("| measured, min / max"))
    assert [tuple(map(float, c.split("/"))) for c in measured.split("|")[2:-1]] == list(
        vc.PPT_MEASURED_KPA)
    cel = next(line for line in page.splitlines() if line.startswith("| CEL mu(t'_N) = 0.25, min"))
    assert [tuple(map(float, c.split("/"))) for c in cel.split("|")[2:-1]] == list(vc.PPT_CEL_KPA)
    assert math.isclose(vc.PPT_A[1], 0.62)


def test_resolutions_recover_the_order_and_the_limit_of_a_known_sequence(tmp_path, capsys):
    """Three runs at cells h = 1, 1/2, 1/3 whose rates are RATE + 0.02 h^2: each row's penetration is
    t (RATE + 0.02 h^2), so the order must come out 2 and the extrapolation t RATE exactly (the
    cycle mean of the sine vanishes to rounding; 1e-6 leaves room for the bisection's and the
    trapezoid's last digits)."""
    specs = []
    for h in (1.0, 0.5, 1.0 / 3.0):
        path = write_history(tmp_path / f"h{h:.3f}.h5", rate=RATE + 0.02 * h ** 2)
        specs.append((h, vc.read_run(path, "vibration")))
    h, rows = vc.resolution_rows(specs, 1.0 / FREQUENCY)
    assert h == sorted(h)
    assert [t for t, _, _ in rows] == list(vc.TIMES)
    for t, f, (f0, band, p) in rows:
        centre = min(t, 3.0 - 0.5 / FREQUENCY)  # the last window moved back to end at 3 s
        assert p == pytest.approx(2.0, abs=1e-6)
        assert f0 == pytest.approx(1e3 * RATE * centre, abs=1e-6)
        assert band == pytest.approx(1.25 * abs(f0 - f[0]), rel=1e-6)
    args = []
    for h in (1.0, 0.5, 1.0 / 3.0):
        args += ["--resolution", f"{tmp_path / f'h{h:.3f}.h5'}:{h!r}"]
    assert vc.main(args) == 0
    # At 1 s: 1e3 (RATE + 0.02 h^2) = 60.2, 63.0, 78.0 mm; the limit 58.0, its band 1.25 x 2.2.
    assert "| 1.00 | 60.2 | 63.0 | 78.0 | 2.00 | 58.0 +- 2.8 | 59.0 | 67.4 |" in capsys.readouterr().out


def test_resolutions_whose_differences_do_not_shrink_give_no_extrapolation(tmp_path, capsys):
    """Rates RATE - 0.02 ln h: the second difference is ln 1.5 / ln 2 = 0.585 of the first, which no
    order in [0.5, 4] makes (0.5 gives 0.53): the rows say so and extrapolate nothing; fewer than
    three runs are refused, and so are a run or --expect beside --resolution and a cell size that
    is not a positive number."""
    args = []
    for h in (1.0, 0.5, 1.0 / 3.0):
        path = write_history(tmp_path / f"h{h:.3f}.h5", rate=RATE - 0.02 * math.log(h))
        args += ["--resolution", f"{path}:{h!r}"]
    assert vc.main(args) == 0
    out = capsys.readouterr().out
    assert out.count("no order: the differences do not shrink as h^p | - |") == len(vc.TIMES)
    with pytest.raises(SystemExit):
        vc.main(args[:4])
    with pytest.raises(SystemExit):
        vc.main([str(tmp_path / "h1.000.h5")] + args)
    with pytest.raises(SystemExit):
        vc.main(args + ["--expect", "1.0=0.5"])
    for size in ("half", "0", "-1", "nan", ""):
        with pytest.raises(SystemExit, match="a positive number"):
            vc.main(args[:4] + ["--resolution", f"{tmp_path / 'h1.000.h5'}:{size}"])


class Snapshot:
    """What tip_zone reads of a snapshot."""

    material_names = ["sand", "pile (rigid)"]

    def __init__(self, positions, material, **arrays):
        self.positions = np.asarray(positions, dtype=float)
        self.arrays = {"material": np.asarray(material), **{k: np.asarray(v, dtype=float) for k, v in arrays.items()}}


def test_the_sand_under_the_tip_its_density_and_what_its_grains_carry():
    """Two rigid particles, the lower at y = 0.5 (the tip); sand at (r, y): two inside the zone (r
    < R = 0.0165 m, 0.5 - R < y < 0.5), one too far out, one too deep, one beside the pile above the
    tip. The saturated stress is total: p' = p + pore_pressure (tension positive), so a particle
    with p = 30 kPa and pore pressure -10 kPa (10 of compression) carries p' = 20 kPa. The two in
    the zone hold half and all of its volume per radian, R^3 / 2: it is filled 1.5 times (per
    unit thickness in plane strain, R^2: 0.75 R times)."""
    third = 0.0165**3 / 2.0
    positions = [(0.005, 0.5), (0.005, 0.55),                   # the pile
                 (0.004, 0.49), (0.012, 0.495),                 # in the zone
                 (0.02, 0.49), (0.004, 0.48), (0.004, 0.51)]    # out, deep, above the tip
    snapshot = Snapshot(positions, [1, 1, 0, 0, 0, 0, 0],
                        volume=[1, 1, 0.5 * third, third, 1, 1, 1],
                        void_ratio=[0, 0, 0.6, 0.8, 5, 5, 5],
                        p=[0, 0, 30e3, 50e3, 9e9, 9e9, 9e9],
                        pore_pressure=[0, 0, -10e3, 30e3, 9e9, 9e9, 9e9],
                        excess_pore_pressure=[0, 0, -8e3, 32e3, 9e9, 9e9, 9e9])
    tip, count, filled, e, effective, excess = vc.tip_zone(snapshot, 0.0165)
    assert (tip, count) == (0.5, 2)
    assert filled == pytest.approx(1.5, rel=1e-12)
    assert vc.tip_zone(snapshot, 0.0165, axisymmetric=False)[2] == pytest.approx(0.75 * 0.0165, rel=1e-12)
    assert e == pytest.approx(0.7, abs=1e-12)
    assert effective == pytest.approx(0.5 * (20.0 + 80.0), abs=1e-9)   # kPa
    assert excess == pytest.approx(-0.5 * (-8.0 + 32.0), abs=1e-9)    # compression positive
    # No sand there: the means are None.
    assert vc.tip_zone(Snapshot(positions[:2], [1, 1], volume=[1, 1], void_ratio=[0, 0], p=[0, 0],
                                pore_pressure=[0, 0], excess_pore_pressure=[0, 0]), 0.0165)[1:] == (
        0, None, None, None, None)
