#!/usr/bin/env python3
"""tools/check_layers.py on small trees made here: layered ones pass, and an include from a lower
folder to a higher one (by its folder, or relative to the file) fails and is named.

    tests/check_layers_test.py   prints "all ok" at the end
"""

import pathlib
import subprocess
import sys
import tempfile

CHECKER = pathlib.Path(__file__).resolve().parent.parent / "tools" / "check_layers.py"


def tree(root: pathlib.Path, files: dict[str, str]) -> pathlib.Path:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


def check(root: pathlib.Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(CHECKER), "--root", str(root)],
                          capture_output=True, text=True)


def main() -> int:
    failures = []
    layered = {
        "engine/grid.hpp": "#pragma once\n#include <vector>\n",
        "engine/materials/soil.hpp": '#include "engine/grid.hpp"\n',
        "solver/step.cpp": '#include "solver/step.hpp"\n#include "engine/grid.hpp"\n',
        "solver/step.hpp": "#pragma once\n",
        "cases/reader.cpp": '#include "solver/step.hpp"\n#include "case_texts.hpp"\n',
        "cases/verification/run.cpp": '#include "cases/reader.hpp"\n',
        "io/history.cpp": '#include "cases/reader.hpp"\n',
        "app/main.cpp": '#include "io/history.hpp"\n#include "cases/verification/run.hpp"\n',
        "tests/helper.hpp": '#include "app/run.hpp"\n',
        "tests/a_test.cpp": '#include "helper.hpp"\n',
    }
    with tempfile.TemporaryDirectory() as directory:
        root = tree(pathlib.Path(directory) / "layered", layered)
        done = check(root)
        if done.returncode != 0 or "layers ok" not in done.stdout:
            failures.append(f"a layered tree failed:\n{done.stdout}{done.stderr}")

        upward = dict(layered)
        upward["cases/geometry_reader.cpp"] = (
            '#include "engine/grid.hpp"\n#include "io/m/vtk.hpp"\n')
        upward["engine/materials/soil.hpp"] = '#include "../../solver/step.hpp"\n'
        root = tree(pathlib.Path(directory) / "upward", upward)
        done = check(root)
        expected = [
            "engine/materials/soil.hpp:1: includes solver/step.hpp: engine/ is below solver/",
            "cases/geometry_reader.cpp:2: includes io/m/vtk.hpp: cases/ is below io/",
            "2 include(s) run up the layers",
        ]
        if done.returncode != 1 or any(line not in done.stdout for line in expected):
            failures.append(f"an upward include was not found:\n{done.stdout}{done.stderr}")

    for failure in failures:
        print(failure)
    if failures:
        return 1
    print("a layered tree passes; upward includes by folder and by relative path are named")
    print("all ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
