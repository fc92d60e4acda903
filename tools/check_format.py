#!/usr/bin/env python3
"""Checks that every C++ source file of the tree is as clang-format writes it (.clang-format).

A file edited by hand (a function renamed and its wrapped arguments left where they were) compiles
and passes its tests, so nothing else notices it. clang-format 14 is Debian 12's; another version
may wrap a line differently, which is why the check names the version it ran.

    tools/check_format.py [--root DIR]

Prints each file clang-format would change, with its first differing line, and exits 1 if there is
one; else prints how many files it read and "format ok". Exits 77 (skipped) without clang-format.
"""

import argparse
import pathlib
import shutil
import subprocess
import sys

from check_unity_names import FOLDERS  # the folders that hold the project's C++


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=pathlib.Path(__file__).resolve().parent.parent,
                        type=pathlib.Path)
    args = parser.parse_args()
    clang_format = shutil.which("clang-format")
    if clang_format is None:
        print("clang-format not found: skipped (Debian: apt-get install clang-format)")
        return 77
    version = subprocess.run([clang_format, "--version"], capture_output=True,
                             text=True).stdout.strip()
    files = sorted(p for folder in FOLDERS for pattern in ("*.cpp", "*.hpp")
                   for p in (args.root / folder).rglob(pattern))
    unformatted = []
    for path in files:
        original = path.read_text()
        # --style=file finds the tree's .clang-format from the file's own folder upwards.
        formatted = subprocess.run([clang_format, "--style=file", str(path)], capture_output=True,
                                   text=True, check=True).stdout
        if formatted != original:
            before, after = original.splitlines(), formatted.splitlines()
            line = next((i for i, (a, b) in enumerate(zip(before, after)) if a != b),
                        min(len(before), len(after)))
            unformatted.append(f"{path.relative_to(args.root)}:{line + 1}: not as clang-format "
                               f"writes it (run clang-format -i on it)")
    print(version)
    for message in unformatted:
        print(message)
    if unformatted:
        return 1
    print(f"{len(files)} files; format ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
