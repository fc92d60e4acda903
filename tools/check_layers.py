#!/usr/bin/env python3
"""Checks that the source folders stand as layers: no file includes a header of a higher folder.

The layers, lowest first. A C or C++ file in one of these folders may include headers of its own
folder and of the folders before it in the list, never of one after it:

    engine   grid, particles, materials, structures, the scene
    solver   the explicit step as passes, the phase runner
    cases    the case format and its readers, the scene and phase builders (the seed's monopile
             among them), element-test and sweep files, the verification cases
    io       what a run writes: histories, snapshots, checkpoints, the output directory
    app      the mpile command line
    tools    the benchmark program (tools/bench/)
    tests    the tests, on top of everything

An include is placed by its first folder ("cases/case_spec.hpp"), or, when that is no layer, by the
path relative to the including file ("case_run.hpp" in tests/). Python files are not checked.

    tools/check_layers.py [--root DIR]

Prints each include that runs up (file:line, the header, the two layers) and exits 1 if there is
one; else prints how many includes it read and "layers ok".
"""

import argparse
import os
import pathlib
import re
import sys

LAYERS = ["engine", "solver", "cases", "io", "app", "tools", "tests"]

SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc", ".cpp.in", ".hpp.in")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layer_of(path: pathlib.PurePosixPath) -> str | None:
    """The layer a path from the root lies in, or None outside every layer."""
    return path.parts[0] if path.parts and path.parts[0] in LAYERS else None


def included_path(root: pathlib.Path, source: pathlib.PurePosixPath, header: str):
    """The included header as a path from the root: by its first folder, else beside the file."""
    written = pathlib.PurePosixPath(header)
    if layer_of(written) is not None:
        return written
    beside = pathlib.PurePosixPath(os.path.normpath(source.parent / written))
    if (root / beside).exists():
        return beside
    return None  # a header of the build (generated) or of a library


def source_files(root: pathlib.Path):
    for layer in LAYERS:
        folder = root / layer
        if not folder.is_dir():
            continue
        for path in sorted(folder.rglob("*")):
            if path.is_file() and path.name.endswith(SOURCE_SUFFIXES):
                yield path


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=pathlib.Path(__file__).resolve().parent.parent,
                        type=pathlib.Path, help="the repository (default: this file's)")
    root = parser.parse_args().root.resolve()
    rank = {layer: i for i, layer in enumerate(LAYERS)}
    includes = 0
    files = 0
    upward = []
    for path in source_files(root):
        source = pathlib.PurePosixPath(path.relative_to(root).as_posix())
        own = layer_of(source)
        files += 1
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
        for number, line in enumerate(lines, start=1):
            match = INCLUDE.match(line)
            if not match:
                continue
            header = included_path(root, source, match.group(1))
            if header is None:
                continue
            includes += 1
            target = layer_of(header)
            if target is not None and rank[target] > rank[own]:
                upward.append(f"{source}:{number}: includes {header}: {own}/ is below {target}/")
    for line in upward:
        print(line)
    if upward:
        print(f"{len(upward)} include(s) run up the layers {' < '.join(LAYERS)}")
        return 1
    print(f"{includes} includes in {files} files; layers ok: {' < '.join(LAYERS)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
