#!/usr/bin/python3
"""tools/results_tables.py on a synthetic run whose values are known exactly, and its check on a
small git history.

The run is tests/make_monopile_history.py's (the pile driven down at 0.1 m/s from the start of its
installation, forces linear in penetration: at 0.1 m tip F_y 50, external F_r -20 and F_y 8,
internal F_r 10 and F_y 4 kN/rad, F_total/F_r 0.5 on both shafts), with /step, wall_time, threads
and the energy residual added. The tables written between a page's markers must hold exactly those
numbers and the runs' commit, and leave the rest of the page alone; `check` must pass a page whose
tables are at its own commit and report one whose runs are older.
"""
import os
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


def check(name, condition, detail=""):
    print(f"{'ok  ' if condition else 'FAIL'} {name}" + (f": {detail}" if detail and not condition else ""))
    return condition


def make_run(directory, commit):
    subprocess.run([sys.executable, str(ROOT / "tests" / "make_monopile_history.py"), str(directory)],
                   check=True, capture_output=True)
    with h5py.File(directory / "history.h5", "a") as history:
        # /step (10 per row) comes with the synthetic history.
        history.attrs["wall_time"] = 12.34
        history.attrs["threads"] = 2.0
        history.attrs["energy_residual_final"] = 0.0012
    (directory / "source_commit").write_text(commit + "\n")


def git(directory, *args):
    return subprocess.run(["git", "-C", str(directory), *args], check=True, capture_output=True,
                          text=True).stdout.strip()


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
        ok &= check("the runs table: steps, wall time, threads, end penetration, residual",
                    "| synthetic | 5 500 | 12.3 | 2 | 0.501 | 0.12 % |" in text, text)
        ok &= check("the forces at 0.05 m", "| synthetic | 0.05 | 0.5000 | 25.0 | -10.0 | 4.0 | 5.0 | 2.0 | 0.500 | 0.500 |"
                    in text, text)
        ok &= check("the forces at 0.1 m", "| synthetic | 0.1 | 1.0000 | 50.0 | -20.0 | 8.0 | 10.0 | 4.0 | 0.500 | 0.500 |"
                    in text, text)
        ok &= check("the markers carry the runs' commit",
                    "<!-- results_tables:begin quick-runs runs=abc1234 -->" in text
                    and "<!-- results_tables:begin quick-forces runs=abc1234 -->" in text)
        ok &= check("the rest of the page is kept",
                    all(s in text for s in ("Text before.\n\n", "\n\nText between.\n\n", "\nText after.\n"))
                    and "old table" not in text and "| old |" not in text)
        again = text
        results_tables.main(["write", f"{run}:synthetic", "--page", str(page)])
        ok &= check("writing twice changes nothing", page.read_text() == again)

        # Runs without a recorded commit are refused unless --commit names it.
        (run / "source_commit").unlink()
        refused = results_tables.main(["write", f"{run}:synthetic", "--page", str(page)])
        ok &= check("a run without a commit is refused", refused == 2)
        results_tables.main(["write", f"{run}:synthetic", "--page", str(page), "--commit", "fff0000"])
        ok &= check("--commit names it", "runs=fff0000 -->" in page.read_text())

        # check: a repository with two commits; the tables at the first.
        repository = base / "repo"
        repository.mkdir()
        git(repository, "init", "-q")
        for key, value in (("user.email", "test@example.com"), ("user.name", "test")):
            git(repository, "config", key, value)
        (repository / "a").write_text("a\n")
        git(repository, "add", "a")
        git(repository, "commit", "-q", "-m", "first")
        first = git(repository, "rev-parse", "--short=7", "HEAD")
        (repository / "a").write_text("b\n")
        git(repository, "commit", "-q", "-am", "second")
        second = git(repository, "rev-parse", "--short=7", "HEAD")
        text = PAGE.format(page=first).replace("runs=unknown", f"runs={first}")
        ok &= check("tables at the page's commit pass", results_tables.check(text, cwd=repository) == [])
        stale = PAGE.format(page=second).replace("runs=unknown", f"runs={first}")
        problems = results_tables.check(stale, cwd=repository)
        ok &= check("tables older than the page's commit are reported, each with its line",
                    len(problems) == 2 and all(f"are older than the page's commit {second}" in p for p in problems)
                    and problems[0].startswith("line 5: table quick-runs"), "\n".join(problems))
        ok &= check("a page without its commit is reported",
                    results_tables.check(PAGE.replace("<!-- results_tables:page-commit {page} -->\n", ""),
                                         cwd=repository) != [])
        ok &= check("source_commit names HEAD", results_tables.source_commit(cwd=repository) == second)
        (repository / "a").write_text("c\n")
        ok &= check("and a modified tree as such", results_tables.source_commit(cwd=repository) == second + "-dirty")
    print("all ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    os.environ.setdefault("GIT_CONFIG_NOSYSTEM", "1")
    sys.exit(main())
