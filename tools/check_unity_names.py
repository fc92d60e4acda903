#!/usr/bin/env python3
"""Checks that no two source files of one folder define the same file-scope name.

The sanitizer builds are unity builds (CMakePresets.json): CMake pastes a target's source files into
batches, and which files share a batch changes whenever a file is added. Two files that each define a
helper `error_of` or a constant `young` in an anonymous namespace compile alone but collide in one
batch. This check finds such pairs before a batch does.

A file-scope name is one declared at the start of a line (column 0, where the project's
clang-format puts the contents of a namespace): a function, a struct, class or enum, or a const or
constexpr variable (each name of a comma list). Raw string literals (the case texts of the tests)
are skipped. Each top-level folder (engine, solver, cases, io, app, tools, tests) is checked as one
unit, as its targets are.

    tools/check_unity_names.py [--root DIR]

Prints each name defined in two files of one folder and exits 1 if there is one; else prints how
many files it read and "unity names ok".
"""

import argparse
import collections
import pathlib
import re
import sys

FOLDERS = ["engine", "solver", "cases", "io", "app", "tools", "tests"]
RAW_STRING = re.compile(r'R"(\w*)\((.*?)\)\1"', re.S)
FUNCTION = re.compile(r"^(?:static |inline |constexpr )*[\w:<>,]+[ &*]+(\w+)\(", re.M)
TYPE = re.compile(r"^(?:struct|class|enum class|enum) (\w+)\b(?!;)", re.M)
VARIABLE = re.compile(r"^(?:static |inline )*(?:constexpr|const) [\w:<>]+ +([^;(]*);", re.M)
NAMES_OF_A_LIST = re.compile(r"(?:^|,)\s*(\w+)\s*(?:=|\{|\[)")


def file_scope_names(text: str) -> set[str]:
    text = RAW_STRING.sub('""', text)
    names = set(FUNCTION.findall(text)) | set(TYPE.findall(text))
    for declaration in VARIABLE.findall(text):
        names.update(NAMES_OF_A_LIST.findall(declaration))
    # `main` and the operators are meant to appear once per program, not per batch.
    return {n for n in names if n != "main" and not n.startswith("operator")}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=pathlib.Path(__file__).resolve().parent.parent)
    root = pathlib.Path(parser.parse_args().root)
    clashes, files = [], 0
    for folder in FOLDERS:
        where = collections.defaultdict(list)
        for path in sorted((root / folder).rglob("*.cpp")):
            files += 1
            for name in file_scope_names(path.read_text(errors="replace")):
                where[name].append(path.relative_to(root).as_posix())
        clashes += [(name, paths) for name, paths in sorted(where.items()) if len(paths) > 1]
    for name, paths in clashes:
        print(f"{name}: defined in {', '.join(paths)} (one unity batch may hold both)")
    if clashes:
        return 1
    print(f"{files} files; unity names ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
