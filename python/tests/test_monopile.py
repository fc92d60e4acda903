"""The installation helpers behind the seed's figures, on the synthetic run whose forces are known:
with s = penetration / 0.1 m, in kN/rad, tip (2 s, 50 s, -4 s), external shaft (-20 s, 8 s, -6 s),
internal shaft (10 s, 4 s, -3 s) for (F_r, F_y, F_theta)."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.files import RunFileError
from mpile.monopile import on_blow_clock, running_mean, shaft_ratios

# The synthetic values are products of exact decimals: relative 1e-12 allows their round-off only.
EXACT = 1e-12


def test_installation_rows_and_forces(synthetic_run):
    run = mpile.installation(synthetic_run)
    assert run.label == "synthetic monopile"
    assert len(run.time) == 501  # the installation's rows only
    assert run.time[0] == pytest.approx(0.01, rel=EXACT)  # the first row after the held phase's last
    row = run.index_at(0.3)
    assert run.penetration[row] == pytest.approx(0.3, rel=EXACT)
    assert run.time[row] == pytest.approx(3.0, rel=EXACT)
    expected = {"tip": (6.0, 150.0, -12.0), "external_shaft": (-60.0, 24.0, -18.0),
                "internal_shaft": (30.0, 12.0, -9.0)}
    for surface, values in expected.items():
        got = [run.forces[surface][c][row] for c in ("F_r", "F_y", "F_theta")]
        assert got == pytest.approx(values, rel=EXACT)
    # The 1e6 N/rad of the held phase stay out.
    assert max(np.abs(run.forces["tip"]["F_r"]).max(), np.abs(run.forces["tip"]["F_y"]).max()) < 300.0
    assert run.index_at(0.6) is None  # 0.5 m reached


def test_row_at_gives_the_values_of_a_row(synthetic_run):
    """row_at is the row (time, penetration and every force there), index_at its index; both None
    beyond the deepest penetration reached."""
    run = mpile.installation(synthetic_run)
    index = run.index_at(0.3)
    assert isinstance(index, int) and run.penetration[index] == pytest.approx(0.3, rel=EXACT)
    row = run.row_at(0.3)
    assert row.index == index
    assert row.penetration == pytest.approx(0.3, rel=EXACT) and row.time == pytest.approx(3.0, rel=EXACT)
    expected = {"tip": (6.0, 150.0, -12.0), "external_shaft": (-60.0, 24.0, -18.0),
                "internal_shaft": (30.0, 12.0, -9.0)}
    assert set(row.forces) == set(expected)
    for surface, values in expected.items():
        assert [row.forces[surface][c] for c in ("F_r", "F_y", "F_theta")] == pytest.approx(values, rel=EXACT)
        assert all(type(row.forces[surface][c]) is float for c in ("F_r", "F_y", "F_theta"))
    assert run.row_at(0.0).index == 0  # the installation's first row
    assert run.row_at(0.6) is None and run.index_at(0.6) is None


def test_shaft_ratios(synthetic_run):
    run = mpile.installation(synthetic_run)
    for surface in ("external_shaft", "internal_shaft"):
        axial, total = shaft_ratios(run.forces[surface])
        assert np.nanmin(axial) == pytest.approx(0.4, rel=1e-9) and np.nanmax(axial) == pytest.approx(0.4, rel=1e-9)
        assert np.nanmin(total) == pytest.approx(0.5, rel=1e-9) and np.nanmax(total) == pytest.approx(0.5, rel=1e-9)
    # Where |F_r| is below 1e-3 of its maximum, no ratio.
    axial, _ = shaft_ratios({"F_r": np.array([1e-6, 1.0]), "F_y": np.array([1.0, 0.4]), "F_theta": np.zeros(2)})
    assert np.isnan(axial[0]) and axial[1] == 0.4


def test_penetration_series_preferred_over_u_y(tmp_path):
    """Newer files hold /bodies/<pile>/penetration; it is the measure, not -u_y."""
    forces = {f"/reactions/pile/{s}/{c}": ([0.0, 1e3, 2e3], "N/rad")
              for s in ("tip", "external_shaft", "internal_shaft") for c in ("F_r", "F_y", "F_theta")}
    series = {"/time": ([0.0, 1.0, 2.0], "s"), "/phase": (np.array([0, 0, 0]), "-"),
              "/bodies/pile/u_y": ([0.0, -1.0, -2.0], "m"), **forces}
    older = write_history(tmp_path / "older.h5", series)
    assert list(mpile.installation(older).penetration) == [0.0, 1.0, 2.0]
    newer = write_history(tmp_path / "newer.h5", {**series, "/bodies/pile/penetration": ([0.0, 0.5, 1.5], "m")})
    assert list(mpile.installation(newer).penetration) == [0.0, 0.5, 1.5]
    with pytest.raises(RunFileError, match="older.h5 has no dataset /bodies/caisson/u_y"):
        mpile.installation(older, body="caisson")


def test_a_run_stopped_before_its_installation_is_refused(tmp_path):
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0], "s"), "/phase": (np.array([0, 0]), "-"), "/bodies/pile/u_y": ([0.0, 0.0], "m"),
        **{f"/reactions/pile/{s}/{c}": ([0.0, 0.0], "N/rad")
           for s in ("tip", "external_shaft", "internal_shaft") for c in ("F_r", "F_y", "F_theta")}},
        attrs={"case_text": '[[phases]]\nname = "geostatic"\n[[phases]]\nname = "installation"\n'})
    with pytest.raises(RunFileError, match="no rows of its last phase \\(index 1\\)"):
        mpile.installation(path)


def test_blow_clock_and_running_mean():
    # Blows 0.1 s apart drawn 0.85 s apart: t = 0.25 s is 0.05 s into blow 2, at 1.7 + 0.05 s.
    assert on_blow_clock(np.array([0.05, 0.25]), 0.1, 0.85) == pytest.approx([0.05, 1.75], rel=EXACT)
    time = np.arange(5.0)
    # Window of 3 rows; ends averaged over the rows there are (2), not padded with zeros.
    assert running_mean(np.array([0.0, 3.0, 6.0, 9.0, 12.0]), time, 3.0) == pytest.approx([1.5, 3.0, 6.0, 9.0, 10.5])
