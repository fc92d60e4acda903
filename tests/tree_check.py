"""A source-tree check of tools/ (check_format.py, check_unity_names.py) run on a small tree of
files written to a temporary directory, as the tests of those checks need it."""

import pathlib
import shutil
import subprocess
import sys
import tempfile

TOOLS = pathlib.Path(__file__).resolve().parent.parent / "tools"


def run_on_tree(checker: str, files: dict[str, str],
                copies: tuple[pathlib.Path, ...] = ()) -> subprocess.CompletedProcess:
    """tools/`checker` with --root at a tree holding `files` ({relative path: text}) and `copies`
    (files copied to its top, such as .clang-format)."""
    with tempfile.TemporaryDirectory() as root:
        for copy in copies:
            shutil.copy(copy, root)
        for name, text in files.items():
            path = pathlib.Path(root) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        return subprocess.run([sys.executable, str(TOOLS / checker), "--root", root],
                              capture_output=True, text=True)


def report(failures: list[str]) -> int:
    """Prints each failure, or "all ok" when there is none (what the test's ctest entry matches);
    the exit status."""
    for failure in failures:
        print("FAIL:", failure)
    if failures:
        return 1
    print("all ok")
    return 0
