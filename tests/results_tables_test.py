#!/usr/bin/python3
"""tools/results_tables.py on a synthetic run whose values are known exactly: the tables it writes,
and its check of a page's tables against runs, which must pass an unchanged table and report a
table edited by one digit.

The run is tests/make_monopile_history.py's (the pile driven down at 0.1 m/s from the start of its
installation, forces linear in penetration: at 0.1 m tip F_y 50, external F_r -20 and F_y 8,
internal F_r 10 and F_y 4 kN/rad, F_total/F_r 0.5 on both shafts), with /step, wall_time, threads
and the energy residual added. The tables written between a page's markers must hold exactly those
numbers and the runs' commit, and leave the rest of the page alone. `check` is run on existing runs
(--runs) and, in its default form, on runs made by a stand-in for mpile that copies the synthetic
run: no engine runs here (the real check is the CTest entry
ResultsTables.PageTablesAgreeWithFreshQuickRuns, a study).
"""
import contextlib
import io
import os
import shutil
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import h5py

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import results_tables  # noqa: E402

PAGE = """# Results
<!-- results_tables:page-commit {page} -->
Text before.

<!-- results_tables:begin quick-runs runs=unknown -->
old table
<!-- results_tables:end quick-runs -->

Text between.

<!-- results_tables:begin quick-forces runs=unknown -->
| old |
<!-- results_tables:end quick-forces -->
Text after.
"""
RUNS_ROW = "| synthetic | 5 500 | 12.3 | 2 | 0.501 | 0.12 % |"
FORCES_AT_0_1 = "| synthetic | 0.1 | 1.0000 | 50.0 | -20.0 | 8.0 | 10.0 | 4.0 | 0.500 | 0.500 |"
RESIDUAL = 0.0012
# Stands in for mpile in `check`'s default form: `run CASE --out DIR --threads N` copies the
# synthetic run into DIR and notes its arguments.
FAKE_MPILE = """#!{python}
import shutil, sys
arguments = sys.argv[1:]
with open({calls!r}, "a") as calls:
    calls.write(" ".join(arguments) + "\\n")
shutil.copytree({template!r}, arguments[arguments.index("--out") + 1], dirs_exist_ok=True)
"""


def check(name, condition, detail=""):
    print(f"{'ok  ' if condition else 'FAIL'} {name}" + (f": {detail}" if detail and not condition else ""))
    return condition


def make_run(directory, commit, residual=RESIDUAL):
    shutil.rmtree(directory, ignore_errors=True)
    subprocess.run([sys.executable, str(ROOT / "tests" / "make_monopile_history.py"), str(directory)],
                   check=True, capture_output=True)
    with h5py.File(directory / "history.h5", "a") as history:
        # /step (10 per row) comes with the synthetic history.
        history.attrs["wall_time"] = 12.34
        history.attrs["threads"] = 2.0
        history.attrs["energy_residual_final"] = residual
    (directory / "source_commit").write_text(commit + "\n")


def set_attribute(directory, key, value):
    with h5py.File(directory / "history.h5", "a") as history:
        history.attrs[key] = value


def main_quietly(*argv):
    """results_tables.main(argv): (exit status, what it printed)."""
    output = io.StringIO()
    with contextlib.redirect_stdout(output), contextlib.redirect_stderr(output):
        status = results_tables.main(list(argv))
    return status, output.getvalue()


def differences(text, run, label="synthetic"):
    return results_tables.compare(text, results_tables.load_runs([run], [label]))


def main():
    ok = True
    with tempfile.TemporaryDirectory() as temporary:
        base = Path(temporary)
        run = base / "run"
        make_run(run, "abc1234")
        page = base / "results.md"
        page.write_text(PAGE.format(page="abc1234"))
        status = results_tables.main(["write", f"{run}:synthetic", "--page", str(page)])
        text = page.read_text()
        ok &= check("write succeeds", status == 0)
        ok &= check("the runs table: steps, wall time, threads, end penetration, residual", RUNS_ROW in text, text)
        ok &= check("the forces at 0.05 m",
                    "| synthetic | 0.05 | 0.5000 | 25.0 | -10.0 | 4.0 | 5.0 | 2.0 | 0.500 | 0.500 |" in text, text)
        ok &= check("the forces at 0.1 m", FORCES_AT_0_1 in text, text)
        ok &= check("the markers carry the runs' commit",
                    "<!-- results_tables:begin quick-runs runs=abc1234 -->" in text
                    and "<!-- results_tables:begin quick-forces runs=abc1234 -->" in text)
        ok &= check("the rest of the page is kept",
                    all(s in text for s in ("Text before.\n\n", "\n\nText between.\n\n", "\nText after.\n"))
                    and "old table" not in text and "| old |" not in text)
        written = text
        results_tables.main(["write", f"{run}:synthetic", "--page", str(page)])
        ok &= check("writing twice changes nothing", page.read_text() == written)

        # Runs without a recorded commit are refused unless --commit names it.
        (run / "source_commit").unlink()
        refused = results_tables.main(["write", f"{run}:synthetic", "--page", str(page)])
        ok &= check("a run without a commit is refused", refused == 2)
        results_tables.main(["write", f"{run}:synthetic", "--page", str(page), "--commit", "fff0000"])
        ok &= check("--commit names it", "runs=fff0000 -->" in page.read_text())
        (run / "source_commit").write_text("abc1234\n")
        page.write_text(written)

        # check --runs: the page just written agrees with its run.
        status, output = main_quietly("check", "--page", str(page), "--runs", f"{run}:synthetic")
        ok &= check("check passes the unchanged tables (exit 0)",
                    status == 0 and "every compared cell agrees" in output, output)
        ok &= check("and notes the tables' runs= commit and the runs'",
                    "quick-runs runs=abc1234" in output and "the runs compared: abc1234" in output, output)

        # One digit edited in each compared column: that cell, and only it, is reported.
        forces_0_1 = ("quick-forces", "synthetic 0.1")
        edits = [
            (RUNS_ROW, "| 5 500 |", "| 5 501 |", ("quick-runs", "synthetic", "steps", "5 501", "5 500")),
            (RUNS_ROW, "| 0.501 |", "| 0.502 |",
             ("quick-runs", "synthetic", "penetration at the end (m)", "0.502", "0.501 (0.501)")),
            (RUNS_ROW, "| 0.12 % |", "| 0.13 % |",
             ("quick-runs", "synthetic", "energy residual at the end", "0.13 %", "0.12 % (0.12)")),
            (FORCES_AT_0_1, "| 1.0000 |", "| 1.0001 |", (*forces_0_1, "time (s)", "1.0001", "1.0000 (1)")),
            (FORCES_AT_0_1, "| 50.0 |", "| 50.1 |", (*forces_0_1, "tip F_y", "50.1", "50.0 (50)")),
            (FORCES_AT_0_1, "| -20.0 |", "| -20.1 |", (*forces_0_1, "ext F_r", "-20.1", "-20.0 (-20)")),
            (FORCES_AT_0_1, "| 8.0 |", "| 8.1 |", (*forces_0_1, "ext F_y", "8.1", "8.0 (8)")),
            (FORCES_AT_0_1, "| 10.0 |", "| 10.1 |", (*forces_0_1, "int F_r", "10.1", "10.0 (10)")),
            (FORCES_AT_0_1, "| 4.0 |", "| 3.9 |", (*forces_0_1, "int F_y", "3.9", "4.0 (4)")),
            (FORCES_AT_0_1, "| 0.500 | 0.500 |", "| 0.501 | 0.500 |",
             (*forces_0_1, "ext F_total/F_r", "0.501", "0.500 (0.5)")),
            (FORCES_AT_0_1, "| 0.500 | 0.500 |", "| 0.500 | 0.499 |",
             (*forces_0_1, "int F_total/F_r", "0.499", "0.500 (0.5)")),
        ]
        for row, old, new, expected in edits:
            edited = written.replace(row, row.replace(old, new, 1))
            found = differences(edited, run)
            ok &= check(f"{expected[2]} edited by one digit is reported", found == [expected], found)
        edited = written.replace(FORCES_AT_0_1, FORCES_AT_0_1.replace("| 50.0 |", "| 50.1 |"))
        page.write_text(edited)
        status, output = main_quietly("check", "--page", str(page), "--runs", f"{run}:synthetic")
        ok &= check("check exits 1 and prints the table, row, column, page's and fresh value",
                    status == 1 and f"{page}: quick-forces: synthetic 0.1: tip F_y: page 50.1, fresh 50.0 (50)\n"
                    in output and "1 difference(s)" in output, output)
        page.write_text(written)

        # Not compared: the wall time (machine dependent) and the thread count.
        edited = written.replace(RUNS_ROW, RUNS_ROW.replace("| 12.3 | 2 |", "| 99.9 | 1 |"))
        ok &= check("the wall time and thread count are not compared", differences(edited, run) == [])

        # The tolerance is half a unit of the last printed digit: 0.12 % holds a residual up to
        # 0.125 %, not beyond.
        set_attribute(run, "energy_residual_final", 0.0012499)
        ok &= check("0.12 % holds a residual of 0.12499 %", differences(written, run) == [])
        set_attribute(run, "energy_residual_final", 0.0012501)
        found = differences(written, run)
        ok &= check("but not 0.12501 %", [d[2:] for d in found] ==
                    [("energy residual at the end", "0.12 %", "0.13 % (0.12501)")], found)
        set_attribute(run, "energy_residual_final", 0.0011499)
        ok &= check("nor 0.11499 %", len(differences(written, run)) == 1)
        set_attribute(run, "energy_residual_final", RESIDUAL)
        set_attribute(run, "wall_time", 99.0)
        ok &= check("a run taking another time still agrees", differences(written, run) == [])

        # Rows without a run, runs without a row, a depth not reached, another header.
        found = differences(written, run, label="renamed")
        ok &= check("a page row with no run and a run with no page row are reported",
                    ("quick-runs", "synthetic", "(row)", "present", "absent (no run of it)") in found
                    and ("quick-runs", "renamed", "(row)", "absent", "present") in found and len(found) == 6, found)
        edited = written.replace(FORCES_AT_0_1, "| synthetic | 0.1 | not reached | | | | | | | |")
        ok &= check("a depth the page says was not reached is reported",
                    differences(edited, run) == [(*forces_0_1, "time (s)", "not reached", "1.0000")])
        edited = written.replace("| tip F_y |", "| tip F_r |")
        ok &= check("a header other than the tool's is reported",
                    [d[:3] for d in differences(edited, run)] == [("quick-forces", "(header)", "(columns)")])
        page.write_text(written.replace("runs=abc1234 -->", "runs= -->", 1))
        status, output = main_quietly("check", "--page", str(page), "--runs", f"{run}:synthetic")
        ok &= check("a malformed marker exits 2", status == 2 and "malformed marker" in output, output)

        # The default form: the four quick cases run by `mpile run` (a stand-in here) into a
        # temporary directory, on two threads, and compared with the page.
        quick = []
        for name, label in results_tables.QUICK_CASES:
            shutil.copytree(run, base / "quick" / name)
            quick.append(f"{base / 'quick' / name}")
        page.write_text(PAGE.format(page="abc1234"))
        status, _ = main_quietly("write", "--page", str(page), *quick)
        four = page.read_text()
        ok &= check("a quick case's directory takes the case's label",
                    status == 0 and "| GDP 414.5 | 5 500 |" in four and "| jacked | 0.1 | 1.0000 |" in four, four)
        calls = base / "calls"
        mpile = base / "mpile"
        mpile.write_text(FAKE_MPILE.format(python=sys.executable, calls=str(calls), template=str(run)))
        mpile.chmod(mpile.stat().st_mode | stat.S_IXUSR)
        status, output = main_quietly("check", "--page", str(page), "--mpile", str(mpile))
        made = calls.read_text().splitlines()
        ok &= check("check runs the four quick cases on two threads and passes their tables",
                    status == 0 and len(made) == 4 and all(
                        call.startswith(f"run {ROOT}/cases/monopile/{name}.toml --out ")
                        and call.endswith(f"/{name} --threads 2")
                        for call, (name, _) in zip(made, results_tables.QUICK_CASES)), output + "\n".join(made))
        ok &= check("in a temporary directory, removed afterwards",
                    not Path(made[0].split(" --out ")[1].split(" ")[0]).parent.exists())
        page.write_text(four.replace("| GDP 829 | 0.05 | 0.5000 | 25.0 |", "| GDP 829 | 0.05 | 0.5000 | 25.1 |"))
        status, output = main_quietly("check", "--page", str(page), "--mpile", str(mpile),
                                      "--out", str(base / "kept"))
        ok &= check("and reports a cell edited by one digit (exit 1)",
                    status == 1 and "quick-forces: GDP 829 0.05: tip F_y: page 25.1, fresh 25.0 (25)" in output, output)
        ok &= check("--out keeps the runs and their logs",
                    (base / "kept" / "gdp829_quick" / "history.h5").is_file()
                    and (base / "kept" / "gdp829_quick.log").is_file())
        failing = base / "failing"
        failing.write_text("#!/bin/sh\necho 'the case is refused'\nexit 3\n")
        failing.chmod(failing.stat().st_mode | stat.S_IXUSR)
        status, output = main_quietly("check", "--page", str(page), "--mpile", str(failing))
        ok &= check("a run that fails exits 2 with its output",
                    status == 2 and "exited with status 3" in output and "the case is refused" in output, output)

        # `run` notes the commit beside each run.
        made_runs = [str(base / "made" / name) for name, _ in results_tables.QUICK_CASES]
        status, _ = main_quietly("run", "--mpile", str(mpile), "--commit", "1234567", *made_runs)
        ok &= check("run writes each run's source_commit",
                    status == 0 and all((Path(d) / "source_commit").read_text() == "1234567\n" for d in made_runs))

        # source_commit: HEAD's short id, "-dirty" for a modified tree.
        repository = base / "repo"
        repository.mkdir()
        git = lambda *args: results_tables.git(*args, cwd=repository)  # noqa: E731
        git("init", "-q")
        for key, value in (("user.email", "test@example.com"), ("user.name", "test")):
            git("config", key, value)
        (repository / "a").write_text("a\n")
        git("add", "a")
        git("commit", "-q", "-m", "first")
        head = git("rev-parse", "--short=7", "HEAD")
        ok &= check("source_commit names HEAD", results_tables.source_commit(cwd=repository) == head)
        (repository / "a").write_text("c\n")
        ok &= check("and a modified tree as such", results_tables.source_commit(cwd=repository) == head + "-dirty")
    print("all ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    os.environ.setdefault("GIT_CONFIG_NOSYSTEM", "1")
    sys.exit(main())
