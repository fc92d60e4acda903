#!/usr/bin/python3
"""Every command README.md and docs/tutorial.md show must name things that exist.

  tests/doc_commands_test.py MPILE [PAGE ...]

In the pages' code (fenced blocks and `inline code`): each `tools/...` path must be a file of the
repository; each `build/release/bin/mpile ...` command must use a subcommand `MPILE --help` lists
(after the global options, e.g. `--threads 1`), and each `cases/...` path it or any command names
must exist (paths with shell variables, globs or an `out/` prefix are runs of the reader's own and
are skipped). `build/release/bin/X` must be a program the build makes (mpile, mpile-bench).
Prints one line per problem and "all ok" when there is none.
"""
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PAGES = ["README.md", "docs/tutorial.md"]
PROGRAMS = {"mpile", "mpile-bench"}
GLOBAL_OPTIONS_WITH_VALUE = {"--threads"}
PATH = re.compile(r"(?<![\w/.-])((?:tools|cases)/[\w./+-]*[\w+-])")
MPILE = re.compile(r"build/release/bin/([\w-]+)((?:[ \t]+[^\s;|&#`]+)*)")


def code_of(text):
    """The page's code: fenced blocks, then inline code spans outside them."""
    fenced = re.findall(r"^```[^\n]*\n(.*?)^```", text, re.MULTILINE | re.DOTALL)
    outside = re.sub(r"^```[^\n]*\n.*?^```", "", text, flags=re.MULTILINE | re.DOTALL)
    inline = re.findall(r"`([^`\n]+)`", outside)
    # Continuation lines joined, so that a command split with "\" is one line.
    return [line for block in fenced + inline for line in block.replace("\\\n", " ").split("\n")]


def subcommands(mpile):
    help_text = subprocess.run([mpile, "--help"], capture_output=True, text=True, check=True).stdout
    section = help_text.split("SUBCOMMANDS:")[-1] if "SUBCOMMANDS:" in help_text else help_text.split("Subcommands:")[-1]
    return set(re.findall(r"^\s+([a-z][\w-]*)\s", section, re.MULTILINE))


def problems_of(page, lines, known):
    problems = []
    for line in lines:
        for path in PATH.findall(line):
            if "$" in path or "*" in path or "{" in path:
                continue
            if not (ROOT / path).exists():
                problems.append(f"{page}: {path} does not exist (in `{line.strip()}`)")
        for program, arguments in MPILE.findall(line):
            if program not in PROGRAMS:
                problems.append(f"{page}: build/release/bin/{program} is not a program the build makes")
                continue
            if program != "mpile":
                continue
            words = arguments.split()
            while words and words[0].startswith("-"):
                words = words[2:] if words[0] in GLOBAL_OPTIONS_WITH_VALUE else words[1:]
            if not words:
                continue  # the program named alone, in prose
            if words[0] not in known:
                problems.append(f"{page}: `mpile {words[0]}` is not a subcommand (known: {', '.join(sorted(known))})"
                                f" in `{line.strip()}`")
    return problems


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    known = subcommands(sys.argv[1])
    if not {"run", "check"} <= known:
        print(f"FAIL: `{sys.argv[1]} --help` lists no run and check subcommands: {sorted(known)}")
        return 1
    pages = sys.argv[2:] or PAGES
    problems = []
    count = 0
    for page in pages:
        lines = code_of((ROOT / page).read_text())
        count += sum(len(PATH.findall(line)) + len(MPILE.findall(line)) for line in lines)
        problems += problems_of(page, lines, known)
    for problem in problems:
        print("FAIL:", problem)
    print(f"{count} paths and commands in {', '.join(pages)}")
    print("all ok" if not problems else f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
