#!/usr/bin/python3
"""The quick-case tables of docs/results.md, written from the runs' history.h5 files and checked
against fresh runs.

  tools/results_tables.py run                  # run the four quick cases one at a time (--threads 2)
  tools/results_tables.py write                # rewrite the tables in docs/results.md from out/*_quick
  tools/results_tables.py check                # run the quick cases afresh, report every cell that differs
  tools/results_tables.py check --runs out/*_quick   # the same against existing runs
  tools/results_tables.py print out/gdp_quick  # the rows of any runs, to the terminal

`run` runs cases/monopile/{jacked,impact,gdp,gdp829}_quick.toml with build/release/bin/mpile (or
--mpile PATH) into out/<case>/ and writes out/<case>/source_commit: the commit checked out when the
run was made (git describe of HEAD, "-dirty" if files outside docs/ differ from it). A run's commit
is --commit if given, else history.h5's `commit` attribute (the commit the program was built from,
written since mpile records it; `mpile --version` prints it too), else that file.

`write` replaces the text between each pair of marker comments in the page,

  <!-- results_tables:begin NAME runs=COMMIT -->
  ...
  <!-- results_tables:end NAME -->

with the table NAME ("quick-runs": steps, run time, threads, penetration and energy residual at the
end; "quick-forces": the time, forces and friction ratios at 0.05 and 0.1 m) and the commit of its
runs. The rows are those `tools/plot_monopile.py --table` prints: the first history row at or beyond
each penetration of the installation (the last phase). All runs of a table must come from one commit.

`check` runs the four quick cases with --threads 2 into a temporary directory (--out DIR keeps
them there instead), or takes the runs given with --runs, recomputes every row of the page's
tables from them and compares each number with the page's, to the digits the page prints them
with (COMPARED below says which columns and why those tolerances). It prints every cell that
differs (table, row, column, the page's value, the fresh one) and exits with status 1 if any
does, 0 if none; 2 if a marker is malformed or a run fails. The runs= commits are printed as a
note only, beside the commit of the runs compared: the numbers decide.

A run directory may be given as DIR:LABEL; without a label, a quick case's directory
(out/gdp_quick, ...) takes the case's label in the tables (GDP 414.5, ...), any other its name.

Uses Debian's python3-h5py and python3-numpy, and the mpile package of this repository (python/).
"""
import argparse
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPOSITORY / "python"))
from mpile.files import RunFileError  # noqa: E402
from mpile.history import attributes, read_series  # noqa: E402
from mpile.monopile import installation, shaft_ratios  # noqa: E402

# The quick cases, in the order of the page's tables: (output directory under out/, label).
QUICK_CASES = [("jacked_quick", "jacked"), ("impact_quick", "impact"),
               ("gdp_quick", "GDP 414.5"), ("gdp829_quick", "GDP 829")]
DEPTHS = (0.05, 0.1)  # m
BEGIN = re.compile(r"^<!-- results_tables:begin (?P<name>[a-z-]+) runs=(?P<commit>\S+) -->$")
END = "<!-- results_tables:end {name} -->"
PAGE_COMMIT = re.compile(r"^<!-- results_tables:page-commit (?P<commit>\S+) -->$", re.MULTILINE)

# Decimals the tables print, shared by `write` and `check` so that check's tolerances follow them.
WALL_DECIMALS = 1  # s
PENETRATION_DECIMALS = 3  # m
RESIDUAL_DECIMALS = 2  # % of the work done
TIME_DECIMALS = 4  # s
FORCE_DECIMALS = 1  # kN/rad
RATIO_DECIMALS = 3
FORCE_COLUMNS = {"tip F_y": ("tip", "F_y"), "ext F_r": ("external_shaft", "F_r"),
                 "ext F_y": ("external_shaft", "F_y"), "int F_r": ("internal_shaft", "F_r"),
                 "int F_y": ("internal_shaft", "F_y")}
RATIO_COLUMNS = {"ext F_total/F_r": "ext_total", "int F_total/F_r": "int_total"}

# The columns `check` compares, by the names in the tables' headers: (how printed, decimals).
#   "count":   an integer with spaces between thousands, compared exactly;
#   "fixed":   a number to `decimals` places;
#   "percent": a fraction as a percentage to `decimals` places, " %" after it.
# The engine gives the same bits for any thread count (ThreadIdentity.* tests) and from one run to
# the next, so a fresh run of the code a table was written from reproduces its numbers exactly: the
# run-to-run spread is zero and the only difference between a page's number and the fresh value is
# the rounding to the printed digits, at most half a unit of the last one (0.05 kN/rad for the
# forces, 0.0005 for the ratios, 0.005 % for the energy residual). Anything more means the code's
# result (or the page) has changed since the table was written: the table is stale. A build by
# another compiler or on other hardware may differ in the last bits, and so at a rounding edge in a
# printed digit; that is a difference of that build and is reported like any other. The step count
# is compared exactly for the same reason. Not compared: the wall time (it depends on the machine and
# on what else runs on it) and the thread count (how the run was made, not what it gave).
COMPARED = {
    "quick-runs": {"steps": ("count", 0), "penetration at the end (m)": ("fixed", PENETRATION_DECIMALS),
                   "energy residual at the end": ("percent", RESIDUAL_DECIMALS)},
    "quick-forces": {"time (s)": ("fixed", TIME_DECIMALS),
                     **{column: ("fixed", FORCE_DECIMALS) for column in FORCE_COLUMNS},
                     **{column: ("fixed", RATIO_DECIMALS) for column in RATIO_COLUMNS}},
}
# The columns that name a row.
ROW_KEYS = {"quick-runs": ("case",), "quick-forces": ("case", "depth (m)")}
NOT_REACHED = "not reached"
# A printed decimal and the binary value it was rounded from, when that value lies at a rounding
# edge (9.75 printed 9.8), are half a unit apart only to within the binary representation's
# round-off, some 1e-16 of their size; this slack, relative to the value, covers that and nothing a
# change of the code could produce in a printed digit.
REPRESENTATION_SLACK = 1e-12


class TableError(Exception):
    pass


def git(*args, cwd=REPOSITORY):
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True).stdout.strip()


def source_commit(cwd=REPOSITORY):
    """HEAD's short commit id, with "-dirty" when files outside docs/ differ from it."""
    commit = git("rev-parse", "--short=7", "HEAD", cwd=cwd)
    changed = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":(exclude)docs", cwd=cwd)
    return commit + ("-dirty" if changed else "")


def run_commit(directory, override=None):
    """The commit a run was made at: --commit, history.h5's `commit` attribute, or source_commit."""
    if override:
        return override
    attrs = attributes(directory)
    if attrs.get("commit"):
        return str(attrs["commit"])
    marker = Path(directory) / "source_commit"
    if marker.is_file():
        return marker.read_text().strip()
    raise TableError(f"{directory}: no commit recorded (history.h5 has no `commit` attribute and there is "
                     f"no source_commit file; make the run with `tools/results_tables.py run` or pass --commit)")


def number(value, decimals):
    formatted = f"{value:.{decimals}f}"
    return formatted.lstrip("-") if float(formatted) == 0.0 else formatted


def summary(directory, label):
    """What the tables need from one run."""
    attrs = attributes(directory)
    steps = read_series(directory, ["/step"])["/step"]
    run = installation(directory, label=label)
    rows = {}
    for depth in DEPTHS:
        row = run.index_at(depth)
        if row is None:
            rows[depth] = None
            continue
        forces = {s: {c: run.forces[s][c][row] for c in ("F_r", "F_y", "F_theta")} for s in run.forces}
        ratio = shaft_ratios({c: run.forces["external_shaft"][c][row:row + 1] for c in ("F_r", "F_y", "F_theta")})
        inner = shaft_ratios({c: run.forces["internal_shaft"][c][row:row + 1] for c in ("F_r", "F_y", "F_theta")})
        rows[depth] = {"time": run.time[row], "forces": forces,
                       "ext_total": float(ratio[1][0]), "int_total": float(inner[1][0])}
    return {"label": label, "steps": int(steps[-1]) if len(steps) else 0,
            "wall": float(attrs.get("wall_time", float("nan"))), "status": attrs.get("status", "?"),
            "threads": attrs.get("threads"), "residual": attrs.get("energy_residual_final"),
            "penetration": float(run.penetration[-1]) if len(run.penetration) else 0.0, "rows": rows}


def residual_text(residual, decimals=RESIDUAL_DECIMALS):
    return f"{100 * float(residual):.{decimals}f} %"


def quick_runs_table(runs):
    lines = ["| case | steps | wall time (s) | threads | penetration at the end (m) | energy residual at the end |",
             "|---|---|---|---|---|---|"]
    for run in runs:
        residual = "" if run["residual"] is None else residual_text(run["residual"])
        threads = "" if run["threads"] is None else f"{float(run['threads']):g}"
        lines.append(f"| {run['label']} | {run['steps']:,} | {run['wall']:.{WALL_DECIMALS}f} | {threads} | "
                     f"{run['penetration']:.{PENETRATION_DECIMALS}f} | {residual} |".replace(",", " "))
    return lines


def quick_forces_table(runs):
    lines = ["| case | depth (m) | time (s) | " + " | ".join([*FORCE_COLUMNS, *RATIO_COLUMNS]) + " |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for run in runs:
        for depth in DEPTHS:
            row = run["rows"][depth]
            if row is None:
                lines.append(f"| {run['label']} | {depth:g} | {NOT_REACHED} | | | | | | | |")
                continue
            f = row["forces"]
            cells = [number(row["time"], TIME_DECIMALS),
                     *(number(f[surface][component], FORCE_DECIMALS) for surface, component in FORCE_COLUMNS.values()),
                     *(number(row[key], RATIO_DECIMALS) for key in RATIO_COLUMNS.values())]
            lines.append(f"| {run['label']} | {depth:g} | " + " | ".join(cells) + " |")
    return lines


TABLES = {"quick-runs": quick_runs_table, "quick-forces": quick_forces_table}


def tables_of(text):
    """[(name, runs commit, begin line index, end line index)] of the page's marked tables."""
    lines = text.split("\n")
    found = []
    for index, line in enumerate(lines):
        match = BEGIN.match(line)
        if not match:
            if line.startswith("<!-- results_tables:begin"):
                raise TableError(f"line {index + 1}: malformed marker {line!r}")
            continue
        name = match["name"]
        if name not in TABLES:
            raise TableError(f"line {index + 1}: unknown table {name!r} (known: {', '.join(TABLES)})")
        try:
            end = lines.index(END.format(name=name), index + 1)
        except ValueError:
            raise TableError(f"line {index + 1}: table {name} has no {END.format(name=name)}") from None
        found.append((name, match["commit"], index, end))
    return found


def replace_tables(text, runs, commit):
    lines = text.split("\n")
    marked = tables_of(text)
    if not marked:
        raise TableError("the page has no results_tables markers")
    for name, _, begin, end in reversed(marked):
        body = TABLES[name](runs)
        lines[begin:end + 1] = [f"<!-- results_tables:begin {name} runs={commit} -->", *body,
                                END.format(name=name)]
    return "\n".join(lines)


def cells_of(line):
    """The cells of a Markdown table row, stripped."""
    return [cell.strip() for cell in line.strip().removeprefix("|").removesuffix("|").split("|")]


def fresh_rows(name, runs):
    """{row key: {column: value}} of table `name` from the runs, unrounded; a depth not reached
    maps to None."""
    rows = {}
    for run in runs:
        if name == "quick-runs":
            rows[(run["label"],)] = {"steps": run["steps"], "penetration at the end (m)": run["penetration"],
                                     "energy residual at the end": run["residual"]}
            continue
        for depth in DEPTHS:
            row = run["rows"][depth]
            rows[(run["label"], f"{depth:g}")] = None if row is None else {
                "time (s)": float(row["time"]),
                **{column: float(row["forces"][surface][component])
                   for column, (surface, component) in FORCE_COLUMNS.items()},
                **{column: float(row[key]) for column, key in RATIO_COLUMNS.items()}}
    return rows


def printed(value, kind, decimals):
    """`value` as the tables print it."""
    if value is None:
        return "(none)"
    if kind == "count":
        return f"{int(value):,}".replace(",", " ")
    if kind == "percent":
        return residual_text(value, decimals)
    return number(value, decimals)


def unrounded(value, kind):
    """`value` to every digit that means something, in the unit the table prints it in."""
    if value is None or kind == "count":
        return ""
    return f" ({100 * float(value) if kind == 'percent' else float(value):.6g})"


def agrees(text, value, kind, decimals):
    """Whether the page's `text` is `value` printed to its digits: a count equal to it, a number no
    farther from it than half a unit of its last printed digit (see COMPARED)."""
    if value is None or text == "":
        return value is None and text == ""
    try:
        if kind == "count":
            return int(text.replace(" ", "")) == int(value)
        if kind == "percent":
            if not text.endswith("%"):
                return False
            page, fresh = float(text.removesuffix("%").strip()), 100 * float(value)
        else:
            page, fresh = float(text), float(value)
    except ValueError:
        return False
    if not math.isfinite(fresh):
        return False
    return abs(page - fresh) <= 0.5 * 10.0 ** -decimals + REPRESENTATION_SLACK * max(1.0, abs(fresh))


def compare(text, runs):
    """The cells of the page's tables that differ from the runs': [(table, row, column, page's
    value, fresh value)], empty if every table agrees. A row of the page that has no run, or a run
    that has no row, and a header other than the tool's are reported too."""
    lines = text.split("\n")
    marked = tables_of(text)
    if not marked:
        raise TableError("the page has no results_tables markers")
    differences = []
    for name, _, begin, end in marked:
        header = TABLES[name]([])[0]
        body = lines[begin + 1:end]
        if not body or body[0].strip() != header:
            differences.append((name, "(header)", "(columns)", body[0].strip() if body else "(none)", header))
            continue
        columns = cells_of(header)
        fresh = fresh_rows(name, runs)
        seen = set()
        for line in body[2:]:
            if not line.strip():
                continue
            cells = cells_of(line)
            if len(cells) != len(columns):
                differences.append((name, line.strip(), "(cells)", len(cells), len(columns)))
                continue
            page = dict(zip(columns, cells))
            key = tuple(page[column] for column in ROW_KEYS[name])
            row = " ".join(key)
            seen.add(key)
            if key not in fresh:
                differences.append((name, row, "(row)", "present", "absent (no run of it)"))
                continue
            values = fresh[key]
            if values is None or page.get("time (s)") == NOT_REACHED:
                if values is not None or page["time (s)"] != NOT_REACHED:
                    differences.append((name, row, "time (s)", page["time (s)"],
                                        NOT_REACHED if values is None else
                                        number(values["time (s)"], TIME_DECIMALS)))
                continue
            for column, (kind, decimals) in COMPARED[name].items():
                if not agrees(page[column], values[column], kind, decimals):
                    differences.append((name, row, column, page[column],
                                        printed(values[column], kind, decimals) +
                                        unrounded(values[column], kind)))
        for key in fresh:
            if key not in seen:
                differences.append((name, " ".join(key), "(row)", "absent", "present"))
    return differences


def commit_note(text, directories):
    """The runs= commits of the page's tables beside those of the runs compared: a note, not a
    verdict (the numbers are compared)."""
    commits = set()
    for directory in directories:
        try:
            commits.add(run_commit(directory))
        except (TableError, RunFileError):
            commits.add("unrecorded")
    stated = PAGE_COMMIT.search(text)
    tables = ", ".join(f"{name} runs={commit}" for name, commit, _, _ in tables_of(text))
    return (f"note: the page's tables: {tables}" + (f" (page-commit {stated['commit']})" if stated else "") +
            f"; the runs compared: {', '.join(sorted(commits))}")


def run_quick_cases(mpile, directories, threads, log_directory=None):
    """Runs the quick cases into `directories`, one at a time. With `log_directory`, each run's
    output goes to <case>.log there and is shown only if the run fails."""
    for (name, _), directory in zip(QUICK_CASES, directories):
        case = REPOSITORY / "cases" / "monopile" / f"{name}.toml"
        print(f"results_tables: {case.name} -> {directory}", flush=True)
        command = [str(mpile), "run", str(case), "--out", str(directory), "--threads", str(threads)]
        started = time.monotonic()
        if log_directory is None:
            status = subprocess.run(command).returncode
        else:
            log = Path(log_directory) / f"{name}.log"
            with open(log, "w") as output:
                status = subprocess.run(command, stdout=output, stderr=subprocess.STDOUT).returncode
        if status != 0:
            tail = "" if log_directory is None else "\n" + "\n".join(log.read_text().splitlines()[-20:])
            raise TableError(f"{' '.join(command)} exited with status {status}{tail}")
        print(f"results_tables: {case.name} done in {time.monotonic() - started:.1f} s", flush=True)


def check(page, directories, labels):
    """Compares the page's tables with the runs; prints each differing cell. 1 if any, else 0."""
    text = Path(page).read_text()
    differences = compare(text, load_runs(directories, labels))
    for table, row, column, page_value, fresh in differences:
        print(f"{page}: {table}: {row}: {column}: page {page_value}, fresh {fresh}")
    print(commit_note(text, directories))
    if differences:
        print(f"{page}: {len(differences)} difference(s) from the runs: the tables are stale")
        return 1
    print(f"{page}: every compared cell agrees with the runs to its printed digits")
    return 0


def load_runs(directories, labels):
    return [summary(directory, label) for directory, label in zip(directories, labels)]


def one_commit(directories, override):
    commits = {str(d): run_commit(d, override) for d in directories}
    if len(set(commits.values())) != 1:
        raise TableError("the runs come from different commits: " +
                         ", ".join(f"{d} at {c}" for d, c in commits.items()))
    return next(iter(commits.values()))


def directory_and_label(spec):
    """DIR[:LABEL] -> (DIR, LABEL); a quick case's directory takes the case's label by default."""
    directory, _, label = spec.partition(":")
    return Path(directory), label or dict(QUICK_CASES).get(Path(directory).name, Path(directory).name)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "write", "check", "print"))
    parser.add_argument("runs", nargs="*", metavar="RUN_DIR[:LABEL]",
                        help="runs (default: out/jacked_quick, out/impact_quick, out/gdp_quick, out/gdp829_quick; "
                             "for check: the quick cases run afresh)")
    parser.add_argument("--runs", dest="run_options", nargs="+", default=[], metavar="RUN_DIR[:LABEL]",
                        help="the same as the positional runs: for check, existing runs instead of fresh ones")
    parser.add_argument("--page", default=str(REPOSITORY / "docs" / "results.md"), help="default docs/results.md")
    parser.add_argument("--commit", help="the commit the runs were made at, when they do not record it")
    parser.add_argument("--mpile", default=str(REPOSITORY / "build" / "release" / "bin" / "mpile"))
    parser.add_argument("--threads", default="2", help="for `run` and `check` (default 2)")
    parser.add_argument("--out", help="for `check`: run the quick cases into this directory and keep them "
                                      "(default: a temporary directory, removed afterwards)")
    args = parser.parse_intermixed_args(argv)

    specs = args.runs + args.run_options
    if specs:
        directories, labels = (list(column) for column in zip(*map(directory_and_label, specs)))
    else:
        directories = [REPOSITORY / "out" / name for name, _ in QUICK_CASES]
        labels = [label for _, label in QUICK_CASES]
    try:
        if args.command == "run":
            commit = args.commit or source_commit()
            run_quick_cases(args.mpile, directories, args.threads)
            for directory in directories:
                (directory / "source_commit").write_text(commit + "\n")
            return 0
        if args.command == "check":
            if specs:
                return check(args.page, directories, labels)
            if args.out:
                base = Path(args.out)
                base.mkdir(parents=True, exist_ok=True)
                fresh = [base / name for name, _ in QUICK_CASES]
                run_quick_cases(args.mpile, fresh, args.threads, log_directory=base)
                return check(args.page, fresh, labels)
            with tempfile.TemporaryDirectory(prefix="results_tables_") as temporary:
                fresh = [Path(temporary) / name for name, _ in QUICK_CASES]
                run_quick_cases(args.mpile, fresh, args.threads, log_directory=temporary)
                return check(args.page, fresh, labels)
        runs = load_runs(directories, labels)
        if args.command == "print":
            for name, table in TABLES.items():
                print(f"{name}:")
                print("\n".join(table(runs)))
            return 0
        commit = one_commit(directories, args.commit)
        page = Path(args.page)
        page.write_text(replace_tables(page.read_text(), runs, commit))
        print(f"{page}: tables written from runs at {commit}")
        return 0
    except (TableError, RunFileError) as error:
        print(f"results_tables: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
