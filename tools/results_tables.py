#!/usr/bin/python3
"""The quick-case tables of docs/results.md, written from the runs' history.h5 files.

  tools/results_tables.py run                  # run the four quick cases one at a time (--threads 2)
  tools/results_tables.py write                # rewrite the tables in docs/results.md from out/*_quick
  tools/results_tables.py check                # report tables whose runs are older than the page's commit
  tools/results_tables.py print out/gdp_quick  # the rows of any runs, to the terminal

`run` runs cases/monopile/{jacked,impact,gdp,gdp829}_quick.toml with build/release/bin/mpile into
out/<case>/ and writes out/<case>/source_commit: the commit checked out when the run was made (git
describe of HEAD, "-dirty" if files outside docs/ differ from it). A run's commit is --commit if
given, else history.h5's `commit` attribute (the commit the program was built from, written since
mpile records it; `mpile --version` prints it too), else that file.

`write` replaces the text between each pair of marker comments in the page,

  <!-- results_tables:begin NAME runs=COMMIT -->
  ...
  <!-- results_tables:end NAME -->

with the table NAME ("quick-runs": steps, run time, energy residual; "quick-forces": the forces at
0.05 and 0.1 m) and the commit of its runs. The rows are those `tools/plot_monopile.py --table`
prints: the first history row at or beyond each penetration of the installation (the last phase).
All runs of a table must come from one commit.

`check` reads the page's own commit, from `<!-- results_tables:page-commit COMMIT -->`, and reports
every table whose runs= commit is not that commit: older (an ancestor of it in git), newer, or
unrelated. Exit status 1 if any table is reported or a marker is malformed, else 0.

Uses Debian's python3-h5py and python3-numpy, and the mpile package of this repository (python/).
"""
import argparse
import re
import subprocess
import sys
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
        row = run.row_at(depth)
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


def quick_runs_table(runs):
    lines = ["| case | steps | wall time (s) | threads | penetration at the end (m) | energy residual at the end |",
             "|---|---|---|---|---|---|"]
    for run in runs:
        residual = "" if run["residual"] is None else f"{100 * float(run['residual']):.2f} %"
        threads = "" if run["threads"] is None else f"{float(run['threads']):g}"
        lines.append(f"| {run['label']} | {run['steps']:,} | {run['wall']:.1f} | {threads} | "
                     f"{run['penetration']:.3f} | {residual} |".replace(",", " "))
    return lines


def quick_forces_table(runs):
    lines = ["| case | depth (m) | time (s) | tip F_y | ext F_r | ext F_y | int F_r | int F_y | "
             "ext F_total/F_r | int F_total/F_r |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for run in runs:
        for depth in DEPTHS:
            row = run["rows"][depth]
            if row is None:
                lines.append(f"| {run['label']} | {depth:g} | not reached | | | | | | | |")
                continue
            f = row["forces"]
            cells = [number(row["time"], 4), number(f["tip"]["F_y"], 1),
                     number(f["external_shaft"]["F_r"], 1), number(f["external_shaft"]["F_y"], 1),
                     number(f["internal_shaft"]["F_r"], 1), number(f["internal_shaft"]["F_y"], 1),
                     number(row["ext_total"], 3), number(row["int_total"], 3)]
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


def relation(older, newer, cwd=REPOSITORY):
    """'same', 'older' (older is an ancestor of newer), 'newer' or 'unrelated' for two commits."""
    strip = [c.removesuffix("-dirty") for c in (older, newer)]
    try:
        full = [git("rev-parse", "--verify", "--quiet", c + "^{commit}", cwd=cwd) for c in strip]
    except subprocess.CalledProcessError:
        return "unknown"
    if full[0] == full[1]:
        return "same" if older == newer else "dirty"
    ancestor = subprocess.run(["git", "merge-base", "--is-ancestor", full[0], full[1]], cwd=cwd).returncode == 0
    if ancestor:
        return "older"
    descendant = subprocess.run(["git", "merge-base", "--is-ancestor", full[1], full[0]], cwd=cwd).returncode == 0
    return "newer" if descendant else "unrelated"


def check(text, cwd=REPOSITORY):
    """The problems of a page's tables, one line each (empty: none)."""
    page = PAGE_COMMIT.search(text)
    if not page:
        return ["the page states no commit (<!-- results_tables:page-commit COMMIT -->)"]
    problems = []
    for name, commit, begin, _ in tables_of(text):
        how = relation(commit, page["commit"], cwd)
        if how == "same":
            continue
        why = {"older": "older than", "newer": "newer than", "unrelated": "not in the history of",
               "dirty": "a modified tree of", "unknown": "not comparable with"}[how]
        problems.append(f"line {begin + 1}: table {name}: its runs (commit {commit}) are {why} "
                        f"the page's commit {page['commit']}")
    return problems


def load_runs(directories, labels):
    return [summary(directory, label) for directory, label in zip(directories, labels)]


def one_commit(directories, override):
    commits = {str(d): run_commit(d, override) for d in directories}
    if len(set(commits.values())) != 1:
        raise TableError("the runs come from different commits: " +
                         ", ".join(f"{d} at {c}" for d, c in commits.items()))
    return next(iter(commits.values()))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "write", "check", "print"))
    parser.add_argument("runs", nargs="*", metavar="RUN_DIR[:LABEL]",
                        help="runs (default: out/jacked_quick, out/impact_quick, out/gdp_quick, out/gdp829_quick)")
    parser.add_argument("--page", default=str(REPOSITORY / "docs" / "results.md"), help="default docs/results.md")
    parser.add_argument("--commit", help="the commit the runs were made at, when they do not record it")
    parser.add_argument("--mpile", default=str(REPOSITORY / "build" / "release" / "bin" / "mpile"))
    parser.add_argument("--threads", default="2", help="for `run` (default 2)")
    args = parser.parse_args(argv)

    if args.runs:
        directories = [Path(spec.partition(":")[0]) for spec in args.runs]
        labels = [spec.partition(":")[2] or Path(spec.partition(":")[0]).name for spec in args.runs]
    else:
        directories = [REPOSITORY / "out" / name for name, _ in QUICK_CASES]
        labels = [label for _, label in QUICK_CASES]
    try:
        if args.command == "run":
            commit = args.commit or source_commit()
            for (name, _), directory in zip(QUICK_CASES, directories):
                case = REPOSITORY / "cases" / "monopile" / f"{name}.toml"
                print(f"results_tables: {case.name} -> {directory}", flush=True)
                subprocess.run([args.mpile, "run", str(case), "--out", str(directory), "--threads", args.threads],
                               check=True)
                (directory / "source_commit").write_text(commit + "\n")
            return 0
        if args.command == "check":
            problems = check(Path(args.page).read_text())
            for problem in problems:
                print(f"{args.page}: {problem}")
            if not problems:
                print(f"{args.page}: every table's runs are at the page's commit")
            return 1 if problems else 0
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
