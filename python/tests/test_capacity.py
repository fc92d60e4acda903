"""The load test of a run: load-settlement curve of its last phase and the capacity at 10 % of D."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.capacity import load_test, moved_zone
from mpile.files import RunFileError

CASE = '[monopile]\ndiameter = 0.5\n[[phases]]\nname = "install"\n[[phases]]\nname = "load_test"\n'


def history(tmp_path):
    # Two rows of the installation (0.1 m reached), then the load test: the pile goes from 0.1 to
    # 0.16 m while the drive's force rises linearly, 1 kN/rad per mm of settlement (driving_F_y
    # is upward positive: the load is its negative).
    # The soil's upward force on the tip is half the load, on each shaft a quarter, plus 1 kN/rad
    # of the pile's weight on the tip.
    depth = np.array([0.0, 0.1, 0.11, 0.12, 0.14, 0.16])
    force = np.array([0.0, -5e3, -10e3, -20e3, -40e3, -60e3])
    return write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0, 2.0, 3.0, 4.0, 5.0], "s"), "/phase": (np.array([0, 0, 1, 1, 1, 1]), "-"),
        "/bodies/pile/penetration": (depth, "m"), "/bodies/pile/driving_F_y": (force, "N/rad"),
        "/reactions/pile/tip/F_y": (1e3 - 0.5 * force, "N/rad"),
        "/reactions/pile/external_shaft/F_y": (-0.25 * force, "N/rad"),
        "/reactions/pile/internal_shaft/F_y": (-0.25 * force, "N/rad")},
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
    assert t.shares == pytest.approx({"tip": 26.0, "external_shaft": 12.5, "internal_shaft": 12.5}, rel=1e-12)


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
    # The load at 0 / 10 / 25 / 50 mm: the first row's (the test's first row lies at 10 mm here),
    # then 1 kN/rad per mm; 50 kN/rad at 0.1 D, 2 pi x 50 kN = 0.314 MN for the whole pile.
    assert ("| known | 0.0600 | 10.0 / 10.0 / 25.0 / 50.0 | 50.0 | 0.314 | 26.0 / 12.5 / 12.5 "
            "| at pile settlement 0.06 m |" in done.stdout.splitlines())
    assert figure.stat().st_size > 10000


def test_a_curve_kept_as_csv_reads_back_as_the_run_and_is_a_run_for_the_tool(tmp_path):
    # --curves writes the run's curve; the CSV, given as a run, gives the tool's row as the history
    # does (to its printed digits), beside the history itself.
    import subprocess
    import sys
    from conftest import REPOSITORY
    from mpile.capacity import read_load_test_csv, write_load_test_csv

    path = history(tmp_path)
    t = load_test(path)
    for name in ("kept.csv", "kept.csv.gz"):
        write_load_test_csv(t, tmp_path / name, source="mpile run x.toml at abc1234")
        back = read_load_test_csv(tmp_path / name)
        assert (back.label, back.diameter, back.ended) == ("known", 0.5, "at pile settlement 0.06 m")
        # Six significant digits: each value within half a unit of its sixth digit.
        assert back.settlement == pytest.approx(t.settlement, rel=5e-6, abs=0)
        assert back.load == pytest.approx(t.load, rel=5e-6, abs=0)
        assert back.capacity == pytest.approx(t.capacity, rel=1e-5)
        assert back.shares == pytest.approx(t.shares, rel=1e-5)
    assert (tmp_path / "kept.csv.gz").read_bytes()[:2] == b"\x1f\x8b"  # gzip's magic
    tool = [sys.executable, str(REPOSITORY / "tools" / "capacity.py")]
    subprocess.run(tool + [f"{path}:known", "--curves", str(tmp_path / "curves"), "--out",
                           str(tmp_path / "a.png")], capture_output=True, text=True, check=True)
    kept = tmp_path / "curves" / "known.csv.gz"
    import gzip
    assert "# source: mpile run ? " in gzip.open(kept, "rt").read()
    again = subprocess.run(tool + [f"{kept}:again", f"{path}:history", "--out", str(tmp_path / "b.png")],
                           capture_output=True, text=True, check=True)
    row = " | 0.0600 | 10.0 / 10.0 / 25.0 / 50.0 | 50.0 | 0.314 | 26.0 / 12.5 / 12.5 | at pile settlement 0.06 m |"
    assert f"| again{row}" in again.stdout.splitlines() and f"| history{row}" in again.stdout.splitlines()
    (tmp_path / "bad.csv").write_text("settlement_m,load_kN_per_rad\n0.1\n")
    with pytest.raises(RunFileError, match="bad.csv:2: 1 values for 2 columns"):
        read_load_test_csv(tmp_path / "bad.csv")


class LatticeSnapshot:
    """What moved_zone reads of a snapshot."""

    material_names = ["sand", "pile (rigid)"]

    def __init__(self, positions, ids, material):
        self.positions = positions
        self.arrays = {"id": ids, "material": material}


def test_the_zone_a_test_moved_is_measured_from_the_particles():
    # Particles at the centres of a 0.01 m lattice on 0 < r < 1 m, 0 < y < 3 m; the wall, rigid,
    # spans r = 0.35 to 0.37 m above y = 2 m (its lowest particles at y = 2.005 m: the tip). The
    # pile settles S = 0.06 m; the sand moves, as fractions of S: below the tip (1 - d / 1 m)(1 - x
    # / 0.2 m) with d the depth below the tip and x the distance out from the wall (0 inside it),
    # the plug 0.5, outside above the tip 0.2 (1 - h / 0.5 m)(1 - x / 0.2 m). Moved by a tenth of S:
    # down to d = 0.9 m, out to x = 0.18 m (just below the tip), up to h = 0.25 m (at the wall).
    # Particles sit on the lattice, so each reach is known to a spacing, 0.01 m.
    centres = 0.005 + 0.01 * np.arange(300)
    r, y = (a.ravel() for a in np.meshgrid(centres[:100], centres))
    pile = (r > 0.35) & (r < 0.37) & (y > 2.0)
    tip, S = 2.005, 0.06
    d, h, x = np.maximum(tip - y, 0.0), np.maximum(y - tip, 0.0), np.maximum(r - 0.37, 0.0)
    fraction = np.where(y < tip, np.maximum(1.0 - d, 0.0) * np.maximum(1.0 - x / 0.2, 0.0),
                        np.where(r < 0.35, 0.5, 0.2 * np.maximum(1.0 - h / 0.5, 0.0) * np.maximum(1.0 - x / 0.2, 0.0)))
    fraction[pile] = 1.0
    ids = np.arange(r.size)
    material = pile.astype(int)  # 1: the rigid pile
    first = LatticeSnapshot(np.column_stack([r, y]), ids, material)
    # The second snapshot re-sorted, as the solver does between snapshots: particles go by id.
    order = np.random.default_rng(1).permutation(r.size)
    moved = np.column_stack([r, y - S * fraction])
    last = LatticeSnapshot(moved[order], ids[order], material[order])
    zone = moved_zone(first, last, 0.1, outer=0.37, inner=0.35)
    assert zone.below_tip == pytest.approx(0.9, abs=0.01)
    assert zone.outside_wall == pytest.approx(0.18, abs=0.01)
    assert zone.above_tip_outside == pytest.approx(0.25, abs=0.01)
    assert zone.plug_follows == pytest.approx(0.5, rel=1e-12)


def test_the_zone_of_a_test_still_going_is_refused(tmp_path):
    from mpile.capacity import load_test_zone
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0], "s"), "/phase": (np.array([0, 1]), "-")},
        attrs={"case_resolved": CASE},
        phases=[{"name": "install", "start": 0.0, "end": 1.0, "ended": "at pile penetration 0.1 m"},
                {"name": "load_test", "start": 1.0}])
    with pytest.raises(RunFileError, match="has no finished load test"):
        load_test_zone(path)


def test_the_sand_an_installation_moved_is_measured_below_the_final_tip():
    # The lattice above, the wall pushed 0.3 m down to its tip at y = 2.005 m. The sand below the
    # tip moves down by 0.02 m (1 - d / 1 m)(1 - x / 0.2 m) (d below the tip before it moved, x out
    # from the wall, 0 under it), the rest not at all. Moved by 5 mm or more: to d = 0.75 m under
    # the wall (0.755 m below the tip where that sand now lies) and x = 0.15 m out (just below the
    # tip, where it moved 5 mm). Each reach is known to a lattice spacing, 0.01 m.
    from mpile.capacity import moved_reach
    centres = 0.005 + 0.01 * np.arange(300)
    r, y = (a.ravel() for a in np.meshgrid(centres[:100], centres))
    pile = (r > 0.35) & (r < 0.37) & (y > 2.0)
    tip = 2.005
    d, x = np.maximum(tip - y, 0.0), np.maximum(r - 0.37, 0.0)
    drop = np.where(y < tip, 0.02 * np.maximum(1.0 - d, 0.0) * np.maximum(1.0 - x / 0.2, 0.0), 0.0)
    drop[pile] = 0.0
    ids = np.arange(r.size)
    material = pile.astype(int)
    first = LatticeSnapshot(np.column_stack([r, np.where(pile, y + 0.3, y)]), ids, material)
    last = LatticeSnapshot(np.column_stack([r, y - drop]), ids, material)
    reach = moved_reach(first, last, 0.005, outer=0.37)
    assert reach.below_tip == pytest.approx(0.755, abs=0.01)
    assert reach.outside_wall == pytest.approx(0.15, abs=0.01)


def test_a_run_without_the_installation_phase_is_refused(tmp_path):
    from mpile.capacity import installation_reach
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0], "s"), "/phase": (np.array([0, 1]), "-")},
        attrs={"case_resolved": CASE},
        phases=[{"name": "install", "start": 0.0, "end": 1.0, "ended": "at pile penetration 0.1 m"},
                {"name": "load_test", "start": 1.0, "end": 2.0}])
    with pytest.raises(RunFileError, match="no finished phase named 'installation'"):
        installation_reach(path, 0.0075)


def test_the_run_record_reads_the_installation_rest_cost_and_ledger(tmp_path):
    # Three phases; the installation's last row (the second) holds its depth and ledger, the
    # rest lasts 0.5 s, the last row the wall time across continuations and the end's residual.
    # The file's attributes are stale on purpose: a run still going wrote them at its last stop.
    from mpile.capacity import run_record
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0, 1.5, 2.0], "s"), "/phase": (np.array([0, 0, 1, 2]), "-"),
        "/step": (np.array([0, 40, 60, 1234567]), "-"),
        "/wall_time": ([0.0, 10.0, 20.0, 10607.8], "s"),
        "/bodies/pile/penetration": ([0.0, 0.3, 0.3, 0.35], "m"),
        "/bodies/pile/driving_F_y": ([0.0, 0.0, 0.0, -1e3], "N/rad"),
        "/energy/relative_residual": ([0.0, 4.6e-4, 1e-3, 5.0e-3], "-")},
        attrs={"case_resolved": '[[phases]]\nname = "installation"\n[[phases]]\nname = "rest"\n'
                                '[[phases]]\nname = "load_test"\n',
               "wall_time": 2355.0, "energy_residual_final": 1.7e-4, "title": "known"},
        phases=[{"name": "installation", "start": 0.0, "end": 1.0, "ended": "at pile penetration 0.3 m"},
                {"name": "rest", "start": 1.0, "end": 1.5, "ended": "after its duration"},
                {"name": "load_test", "start": 1.5, "end": 2.0, "ended": "at pile settlement 0.05 m"}])
    record = run_record(path)
    assert (record.depth, record.installed_at, record.steps) == (0.3, 1.0, 1234567)
    assert record.rest == pytest.approx(0.5, rel=1e-12)
    assert (record.wall_time, record.ledger_installed, record.ledger_end) == (10607.8, 4.6e-4, 5.0e-3)
    # Its case names no diameter: no capacity, and no crash reading one (the tool's row below).
    assert np.isnan(load_test(path).capacity)

    import subprocess
    import sys
    from conftest import REPOSITORY
    done = subprocess.run([sys.executable, str(REPOSITORY / "tools" / "capacity.py"), f"{path}:GDP, HS",
                           "--record", "--out", str(tmp_path / "c.png")], capture_output=True, text=True,
                          check=True)
    # Two significant digits of each residual in %, the counts in groups of three, the label's comma kept.
    assert "| GDP, HS | 0.300 at 1.000 | 0.5 | 1 234 567 | 10 608 | 0.046 / 0.50 % |" in done.stdout.splitlines()


def test_the_fill_at_the_wall_tip_is_once_for_consistent_particles_and_twice_for_crowded_ones():
    # A 5 mm lattice of particles on 0.3 < r < 0.45 m, 1.9 < y < 2.1 m, each with the volume per
    # radian of its square, r h^2; the wall's (rigid) span r = 0.35 to 0.37 m above y = 2.0 m,
    # the lowest centred at 2.0025 m, its lower edge (the tip) at 2.0 m. Each zone, 0.02 m wide
    # and deep below the tip, holds whole squares, whose midpoint sum of r h^2 is the zone's
    # integral of r exactly: each is filled once. Doubling the volumes of the particles under the
    # wall fills that zone twice.
    from mpile.capacity import wall_tip_fill

    class Lattice:
        material_names = ["sand", "pile (rigid)"]
        time = 1.5

        def __init__(self, positions, material, volume):
            self.positions = positions
            self.arrays = {"material": material, "volume": volume}

    h = 0.005
    r, y = (a.ravel() for a in np.meshgrid(0.3 + h * (np.arange(30) + 0.5), 1.9 + h * (np.arange(40) + 0.5)))
    wall = (r > 0.35) & (r < 0.37) & (y > 2.0)
    soil_r, soil_y = r[~wall], y[~wall]
    positions = np.column_stack([np.concatenate([soil_r, r[wall]]), np.concatenate([soil_y, y[wall]])])
    material = np.concatenate([np.zeros(soil_r.size, int), np.ones(wall.sum(), int)])
    volume = np.concatenate([soil_r, r[wall]]) * h * h
    fill = wall_tip_fill(Lattice(positions, material, volume), outer=0.37, inner=0.35)
    assert (fill.time, fill.under, fill.inside, fill.outside) == pytest.approx((1.5, 1.0, 1.0, 1.0), rel=1e-12)
    under = (positions[:, 0] > 0.35) & (positions[:, 0] < 0.37) & (positions[:, 1] < 2.0)
    crowded = np.where(under & (material == 0), 2.0 * volume, volume)
    assert wall_tip_fill(Lattice(positions, material, crowded), 0.37, 0.35).under == pytest.approx(2.0, rel=1e-12)
