#!/usr/bin/env python3
"""tools/check_format.py on small trees made here, with the project's .clang-format: a formatted
file passes; a call whose wrapped argument is left where it was before a rename fails and is named
with its line; a file outside the checked folders is not read.

    tests/check_format_test.py   prints "all ok" at the end (exit 77 without clang-format)
"""

import pathlib
import shutil
import sys

from tree_check import report, run_on_tree

ROOT = pathlib.Path(__file__).resolve().parent.parent

FORMATTED = "int twice(int x) {\n  return 2 * x;\n}\n"
# As a rename leaves it: the continuation still aligned under the old, shorter name's parenthesis.
LEFT_BEHIND = ("void add_displacement_increment(const std::vector<double>& first_argument,\n"
               "                  const std::vector<double>& second_argument_of_the_call);\n")


def check(files: dict[str, str]):
    return run_on_tree("check_format.py", files, copies=(ROOT / ".clang-format",))


def main() -> int:
    if shutil.which("clang-format") is None:
        print("clang-format not found: skipped")
        return 77
    failures = []
    clean = check({"engine/a.cpp": FORMATTED, "docs/b.cpp": LEFT_BEHIND})
    if clean.returncode != 0 or "1 files; format ok" not in clean.stdout:
        failures.append(f"a formatted tree (and a file outside the folders) failed: {clean.stdout}")
    dirty = check({"engine/a.cpp": FORMATTED, "solver/c.hpp": LEFT_BEHIND})
    if dirty.returncode != 1 or "solver/c.hpp:2: not as clang-format writes it" not in dirty.stdout:
        failures.append(f"the left-behind line was not named: {dirty.stdout}")
    if "engine/a.cpp" in dirty.stdout:
        failures.append(f"the formatted file was named: {dirty.stdout}")
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
