"""phases(): the recorded /phases table, or one rebuilt from case_text and the /phase series."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.files import RunFileError


def test_rebuilt_from_the_case_and_rows(synthetic_run):
    """No /phases in the synthetic file: the installation starts at the last held row (0.49 s)."""
    table = mpile.phases(synthetic_run)
    assert list(table.columns) == ["name", "start", "end", "ended"]
    assert list(table["name"]) == ["equilibrium", "installation"]
    assert table["start"].tolist() == pytest.approx([0.0, 0.49], abs=1e-12)  # 49 * 0.01 in floating point
    assert table["end"].tolist() == pytest.approx([0.49, 5.5], abs=1e-12)
    assert table["ended"].isna().all()  # why they ended is not in older files


def test_recorded_table_wins_and_unreached_phases_are_listed(tmp_path):
    case = '[[phases]]\nname = "a"\n[[phases]]\nname = "b"\n[[phases]]\nname = "c"\n'
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0, 2.0], "s"), "/phase": (np.array([0, 0, 1]), "-")},
        attrs={"case_text": case, "status": "running"},
        phases=[{"name": "a", "start": 0.0, "end": 1.25, "ended": "at equilibrium"},
                {"name": "b", "start": 1.25}])
    table = mpile.phases(path)
    assert list(table["name"]) == ["a", "b", "c"]
    assert table.loc[0, "end"] == 1.25 and table.loc[0, "ended"] == "at equilibrium"
    assert table.loc[1, "start"] == 1.25
    assert np.isnan(table.loc[1, "end"]) and table.loc[1, "ended"] is None  # still going
    assert np.isnan(table.loc[2, "start"])  # not reached


def test_a_run_stopped_early_leaves_the_last_phase_open(tmp_path):
    path = write_history(tmp_path / "history.h5", {
        "/time": ([0.0, 1.0, 2.0], "s"), "/phase": (np.array([0, 1, 1]), "-")},
        attrs={"case_text": '[[phases]]\nname = "a"\n[[phases]]\nname = "b"\n', "status": "interrupted"})
    table = mpile.phases(path)
    assert table["start"].tolist() == [0.0, 0.0]  # b starts at a's last row, t = 0
    assert table.loc[0, "end"] == 0.0 and np.isnan(table.loc[1, "end"])


def test_refuses_a_missing_file(tmp_path):
    with pytest.raises(RunFileError, match="missing.h5"):
        mpile.phases(tmp_path / "missing.h5")


def test_real_run(real_run):
    table = mpile.phases(real_run)
    assert list(table["name"]) == ["slide"]
    assert table.loc[0, "start"] == 0.0
    assert table.loc[0, "end"] == pytest.approx(1.0, abs=1e-9)  # duration = 1.0
    assert table.loc[0, "ended"] == "after its duration"
