"""Cases from Python (mpile.Case, run_sweep): values set are checked by the mpile program as the
command line's --set is, reach the run exactly, and a written case runs as the same case; runs on
1 and 2 threads write the same history; a list of cases runs through mpile sweep.

V7 (an elastic block sliding down an incline, cut to 0.2 s: about 0.1 s a run) and V2 (one material
point on a spring) are the runs."""
import math
import subprocess
import tomllib

import h5py
import numpy as np
import pytest
from conftest import REPOSITORY, mpile_binary

import mpile
from mpile import cases
from mpile.cases import toml_value

V7 = REPOSITORY / "cases" / "verification" / "v7_block_on_incline.toml"
V2 = REPOSITORY / "cases" / "verification" / "single_point.toml"
DENSITY = 1000.0 + 1.0 / 3.0  # not a short decimal: 1000.3333333333334 is its repr


@pytest.fixture(scope="module")
def binary():
    found = mpile_binary()
    if found is None:
        pytest.skip("no mpile program: set MPILE to its path (ctest does)")
    return found


def same_series(first, second, leave_out=("wall_time",)):
    """The names of the datasets that differ between two history.h5 files (all but `leave_out`)."""
    differ = []
    with h5py.File(first, "r") as a, h5py.File(second, "r") as b:
        names = []
        a.visititems(lambda name, node: names.append(name) if isinstance(node, h5py.Dataset) else None)
        other = []
        b.visititems(lambda name, node: other.append(name) if isinstance(node, h5py.Dataset) else None)
        assert sorted(names) == sorted(other)
        for name in names:
            nan = a[name].dtype.kind == "f"
            if name not in leave_out and not np.array_equal(a[name][()], b[name][()], equal_nan=nan):
                differ.append(name)
    return differ, len(names)


def test_python_values_become_toml_values_that_read_back():
    values = [0.1, 0.1 + 0.2, 1.0 / 3.0, 5e-324, 1.7976931348623157e308, 1e16, 1e-5, -2.5, 123456789.123456789,
              3, -7, 2**62, True, False, "plain", 'a "quoted" \\ back\\slash', "line\nbreak\ttab\x01\x7f", "é ✓",
              [1.0, [2, "x"], []], {"velocity_y": -0.2, "a key": [True]}]
    for value in values:
        assert tomllib.loads("x = " + toml_value(value))["x"] == value, toml_value(value)
    assert toml_value(0.1 + 0.2) == "0.30000000000000004"
    assert math.copysign(1.0, tomllib.loads("x = " + toml_value(-0.0))["x"]) == -1.0
    assert [toml_value(v) for v in (math.inf, -math.inf)] == ["inf", "-inf"]
    assert math.isnan(tomllib.loads("x = " + toml_value(math.nan))["x"])
    assert toml_value(np.float64(DENSITY)) == repr(DENSITY) and toml_value(np.int64(4)) == "4"
    assert toml_value(np.bool_(True)) == "true" and toml_value(np.array([0.5, 2.0])) == "[0.5, 2.0]"
    for refused in (None, object(), {1: 2.0}):
        with pytest.raises(TypeError, match="TOML"):
            toml_value(refused)


def test_the_program_is_found_from_the_argument_then_MPILE_then_PATH(binary, tmp_path, monkeypatch):
    monkeypatch.setenv("MPILE", str(tmp_path / "nowhere"))
    assert cases.find_mpile(binary) == binary  # the argument first
    with pytest.raises(cases.MpileNotFoundError, match=r"MPILE names '.*nowhere', which is not an executable file"):
        cases.find_mpile()
    monkeypatch.setenv("MPILE", binary)
    assert cases.find_mpile() == binary
    assert mpile.Case(V7).mpile == binary
    monkeypatch.delenv("MPILE")
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setattr(cases, "_SOURCE_TREE_BUILD", tmp_path / "build" / "mpile")
    with pytest.raises(cases.MpileNotFoundError, match="no mpile program: pass mpile=PATH, set the MPILE"):
        cases.find_mpile()
    (tmp_path / "mpile").symlink_to(binary)
    assert cases.find_mpile() == str(tmp_path / "mpile")


def test_a_set_is_checked_by_mpile_as_on_the_command_line(binary):
    case = mpile.Case.read(V7, mpile=binary)
    case["phases.slide.duration"] = 0.2  # an element of [[phases]] by its name, as --set takes it
    assert case.overrides == ["phases.slide.duration=0.2"]
    with pytest.raises(mpile.CaseError) as refused:
        case["phases.slide.durationx"] = 1.0
    # The message is mpile check's, word for word, with its status.
    shell = subprocess.run([binary, "check", str(V7), "--set", "phases.slide.duration=0.2", "--set",
                            "phases.slide.durationx=1.0"], capture_output=True, text=True)
    assert shell.returncode == 2 and refused.value.status == 2
    assert str(refused.value) == shell.stderr.strip().removeprefix("mpile: ")
    assert str(refused.value).startswith("--set phases.slide.durationx:1: phases[0].durationx: unknown key")
    assert isinstance(refused.value, ValueError)
    assert case.overrides == ["phases.slide.duration=0.2"]  # a refused set leaves the case as it was
    with pytest.raises(mpile.CaseError, match=r"^--set materials.block.density:1: materials.block.density: "
                                              r"expected a number, got a string"):
        case.set("materials.block.density", "1000")
    with pytest.raises(mpile.CaseError, match=r"materials.block.density: linear_elastic: density must be > 0"):
        case.set("materials.block.density", -5.0)
    with pytest.raises(mpile.CaseError, match="not a key path"):
        case.set("title=x", 1)
    with pytest.raises(mpile.CaseError, match="cannot open the case file"):
        mpile.Case.read(V7.with_name("no_such_case.toml"), mpile=binary)
    # Setting a key again replaces its value; a copy changes alone.
    other = case.copy().set("phases.slide.duration", 0.1)
    assert other.overrides == ["phases.slide.duration=0.1"] and case.overrides == ["phases.slide.duration=0.2"]
    case.update({"materials.block.density": DENSITY, "title": 'V7 "from Python"'})
    assert case["materials.block.density"] == DENSITY  # the resolved case's value, read back exactly
    assert case["phases.slide.duration"] == 0.2 and case["title"] == 'V7 "from Python"'
    with pytest.raises(KeyError, match="no 'nothing'"):
        case["solver.nothing"]
    del case["title"]
    assert case.overrides == ["phases.slide.duration=0.2", f"materials.block.density={DENSITY!r}"]


@pytest.fixture(scope="module")
def v7_runs(binary, tmp_path_factory):
    """V7 for 0.2 s with a density that is no short decimal, run on 1 and on 2 threads."""
    directory = tmp_path_factory.mktemp("v7_case")
    case = mpile.Case.read(V7, mpile=binary).update({"phases.slide.duration": 0.2, "materials.block.density": DENSITY})
    return case, case.run(directory / "one", threads=1), case.run(directory / "two", threads=2)


def test_a_run_holds_the_values_set_exactly(v7_runs):
    case, run, _ = v7_runs
    assert run.status == "complete" and mpile.open_history(run).attrs["status"] == "complete"
    ran = mpile.case(run)  # the history's case_resolved
    assert ran["materials"]["block"]["density"] == DENSITY
    assert ran["phases"][0]["duration"] == 0.2
    assert run.attributes()["overrides"].splitlines() == case.overrides
    time = run.history()["time"].values
    assert time[-1] == pytest.approx(0.2, abs=1e-3) and time[-2] < 0.2


def test_thread_counts_give_identical_histories(v7_runs):
    _, one, two = v7_runs
    assert (one.attributes()["threads"], two.attributes()["threads"]) == (1, 2)
    differ, count = same_series(one.directory / "history.h5", two.directory / "history.h5")
    assert differ == [] and count > 20


def test_a_written_case_runs_as_the_same_case(binary, v7_runs, tmp_path):
    case, run, _ = v7_runs
    written = case.write(tmp_path / "variant.toml")
    assert subprocess.run([binary, "check", str(written)], capture_output=True).returncode == 0
    assert tomllib.loads(written.read_text())["materials"]["block"]["density"] == DENSITY
    again = tmp_path / "again"
    subprocess.run([binary, "run", str(written), "--out", str(again), "--threads", "1"], check=True,
                   capture_output=True, timeout=120)
    assert mpile.attributes(again)["case_resolved"] == run.attributes()["case_resolved"]
    differ, _ = same_series(run.directory / "history.h5", again / "history.h5")
    assert differ == []
    # Read back as a case, with no --set: the same resolved case.
    assert mpile.Case.read(written, mpile=binary).resolved_text() == case.resolved_text()


def test_run_streams_progress_stops_and_reports_failures(binary, tmp_path):
    case = mpile.Case.read(V7, mpile=binary).set("phases.slide.duration", 0.05)
    lines = []
    stopped = case.run(tmp_path / "stopped", progress=lines.append, stop_after=5)
    assert "phase slide from t = 0 s" in lines
    assert stopped.status.startswith("interrupted at t = ") and stopped.history()["step"].values.max() <= 5
    resumed = case.run(tmp_path / "stopped", resume=True, progress=lines.append)
    assert resumed.status == "complete" and any("continuing" in line for line in lines)
    case.set("phases.slide.durationx", 1.0, check=False)  # left to the run, which refuses it
    with pytest.raises(mpile.CaseError, match=r"^--set phases.slide.durationx:1: phases\[0\].durationx: "
                                              r"unknown key") as refused:
        case.run(tmp_path / "refused")
    assert refused.value.status == 2
    # V2 at 4 m/s for 2 s: the point leaves its one-cell grid (exit status 1).
    leaving = mpile.Case.read(V2, mpile=binary).update({"bodies.0.velocity": [4.0, 0.0, 0.0],
                                                        "phases.0.duration": 2.0})
    with pytest.raises(mpile.RunError, match=r"particle 0 at .* left the grid") as failed:
        leaving.run(tmp_path / "leaving")
    assert failed.value.status == 1 and failed.value.run.status.startswith("failed")


def test_run_sweep_runs_a_list_of_cases(binary, tmp_path):
    """Two variants of V2 (two stiffnesses, given stiffer first) through mpile sweep on one core."""
    base = mpile.Case.read(V2, mpile=binary).set("phases.0.duration", 0.2)
    moduli = [157.91367041742973, 39.47841760435743]  # omega = 4 pi, 2 pi
    variants = [base.copy().set("materials.spring.young_modulus", modulus) for modulus in moduli]
    gather = [{"name": "kinetic_start", "series": "energy/kinetic", "at_time": 0.0},
              {"name": "kinetic_quarter", "series": "energy/kinetic", "at_time": 0.125}]
    study = mpile.run_sweep(variants, tmp_path / "sweep", gather=gather, cores=1)
    sweep_file = tomllib.loads((tmp_path / "sweep" / "study.toml").read_text())
    assert sweep_file["set"] == ["phases.0.duration=0.2"]
    assert sweep_file["parameters"] == {"materials.spring.young_modulus": moduli}
    assert study.variants == ["v01", "v02"]
    table = study.results(form="pandas")
    assert list(table["variant"]) == ["v01", "v02"] and list(table["status"]) == ["finished", "finished"]
    assert list(table["materials.spring.young_modulus"]) == moduli
    # 0.5 m v0^2 at t = 0 (m = 1 kg per metre, v0 = 0.1 m/s); a quarter period of the stiffer spring
    # in (0.125 s) its energy is nearly all elastic, of the softer (0.25 s) still half kinetic.
    np.testing.assert_allclose(table["kinetic_start"], 0.005, rtol=1e-12)
    assert table["kinetic_quarter"][0] < 0.01 * 0.005 and table["kinetic_quarter"][1] > 0.3 * 0.005
    for index, modulus in enumerate(moduli):
        assert mpile.case(study.run(index))["materials"]["spring"]["young_modulus"] == modulus
    assert mpile.open_sweep(study)["kinetic_start"].sizes == {"materials.spring.young_modulus": 2}


def test_run_sweep_takes_cases_of_one_file_in_every_combination(tmp_path):
    """Refused before anything runs, so no program is needed."""
    def variant(path=V2, **values):
        return mpile.Case(path).update({k.replace("__", "."): v for k, v in values.items()}, check=False)

    grid = [variant(a__b=a, c__d=c) for a in (1.0, 2.0) for c in ("x", "y", "z")]
    text, positions = cases.sweep_file_text(grid[::-1], gather=[{"name": "e", "series": "energy/kinetic",
                                                                 "reduce": "max"}])
    parsed = tomllib.loads(text)
    assert parsed["parameters"] == {"a.b": [2.0, 1.0], "c.d": ["z", "y", "x"]} and parsed["case"] == str(V2)
    assert positions == list(range(6)) and parsed["gather"] == [{"name": "e", "series": "energy/kinetic",
                                                                  "reduce": "max"}]
    with pytest.raises(ValueError, match=r"not every combination of their values \(a.b = 2.0, c.d = \"z\""):
        cases.sweep_file_text(grid[:-1])
    with pytest.raises(ValueError, match="cases 0 and 6 are the same variant"):
        cases.sweep_file_text(grid + grid[:1])
    with pytest.raises(ValueError, match="a sweep runs one case file"):
        cases.sweep_file_text([variant(a__b=1.0), variant(V7, a__b=2.0)])
    with pytest.raises(ValueError, match="e.f is set in some cases and not in case 0"):
        cases.sweep_file_text([variant(a__b=1.0), variant(a__b=2.0, e__f=1)])
    with pytest.raises(ValueError, match="the cases do not differ"):
        cases.sweep_file_text([variant(a__b=1.0)])
