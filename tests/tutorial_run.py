#!/usr/bin/python3
"""docs/tutorial.md, run as written but cut short: its shell and Python blocks in order.

  tests/tutorial_run.py MPILE SCRATCH_DIR

The commands run in SCRATCH_DIR, which mirrors the repository (tools/, cases/, python/ linked, and
build/release/bin/mpile linked to MPILE), so that their out/ directories land there. Changes to
the commands, so that the whole tutorial takes a minute or two on two cores:

- `bash tools/run-main.sh ARGS` runs the main job's steps after the set-up and build (those lines
  of tools/run-main.sh from `out=` on), with ARGS;
- every `mpile run` of a monopile case stops its installation at 0.02 m
  (`--set phases.1.stop_at.penetration=0.02`), and a restart's new target becomes 0.03 m;
- `pvpython tools/paraview_open_run.py RUN` runs with --plan-only under python3 when there is no
  pvpython;
- a Python block's comment line `# build/release/bin/mpile ...` is run as the command it shows
  before the block; the Python blocks run in one interpreter, in order, matplotlib drawing to files.

Fails at the first command that fails, naming it; prints "tutorial ok" at the end.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TUTORIAL = ROOT / "docs" / "tutorial.md"
SHORT = "0.02"  # m: the installations' stop
RESTART_TARGET = "0.03"  # m: a restart's new stop


def blocks(text):
    """[(language, code)] of the page's fenced blocks, in order."""
    return re.findall(r"^```(\w*)\n(.*?)^```", text, re.MULTILINE | re.DOTALL)


def commands(code):
    """The commands of a shell block: comments dropped, continuation lines joined."""
    joined = code.replace("\\\n", " ")
    lines = [re.sub(r"\s+#.*$", "", line).strip() for line in joined.split("\n")]
    return [line for line in lines if line and not line.startswith("#")]


def shortened(command):
    if re.search(r"build/release/bin/mpile\s+run\s+cases/monopile/", command):
        if "--restart" in command:
            return re.sub(r"(phases\.1\.stop_at\.penetration=)[0-9.]+", rf"\g<1>{RESTART_TARGET}", command)
        return command + f" --set phases.1.stop_at.penetration={SHORT}"
    return command


def main_job(arguments):
    """tools/run-main.sh from its `out=` line on: the run and the figures, not set-up and build."""
    script = (ROOT / "tools" / "run-main.sh").read_text().split("\n")
    start = next(i for i, line in enumerate(script) if line.startswith("out="))
    body = "\n".join(script[start:])
    return f"set -euo pipefail\nset -- {arguments} --set phases.1.stop_at.penetration={SHORT}\n{body}"


def run(command, cwd, shell_script=None):
    print(f"$ {command}", flush=True)
    if shell_script is not None:
        done = subprocess.run(["bash", "-c", shell_script], cwd=cwd)
    else:
        done = subprocess.run(["bash", "-c", "set -euo pipefail\n" + command], cwd=cwd)
    if done.returncode != 0:
        print(f"FAIL: `{command}` exited with {done.returncode}")
        sys.exit(1)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    mpile, scratch = Path(sys.argv[1]).resolve(), Path(sys.argv[2])
    if scratch.exists():
        shutil.rmtree(scratch)
    (scratch / "build" / "release" / "bin").mkdir(parents=True)
    for name in ("tools", "cases", "python"):
        (scratch / name).symlink_to(ROOT / name)
    (scratch / "build" / "release" / "bin" / "mpile").symlink_to(mpile)
    os.environ["MPLBACKEND"] = "Agg"
    pvpython = shutil.which("pvpython")
    python_code = []
    ran = 0
    for language, code in blocks(TUTORIAL.read_text()):
        if language == "sh":
            for command in commands(code):
                main = re.match(r"bash tools/run-main\.sh\s*(.*)$", command)
                if main:
                    run(command, scratch, main_job(main.group(1)))
                elif command.startswith("pvpython ") and not pvpython:
                    run(command.replace("pvpython", "/usr/bin/python3", 1) + " --plan-only", scratch)
                else:
                    run(shortened(command), scratch)
                ran += 1
        elif language == "python":
            for line in code.split("\n"):
                shown = re.match(r"#\s*(build/release/bin/mpile .*)$", line.strip())
                if shown:
                    run(shortened(shown.group(1)), scratch)
                    ran += 1
            python_code.append(code)
    if python_code:
        print("$ python3 (the tutorial's Python blocks)", flush=True)
        done = subprocess.run(["/usr/bin/python3", "-c", "\n".join(python_code)], cwd=scratch)
        if done.returncode != 0:
            print("FAIL: the tutorial's Python blocks")
            return 1
        ran += 1
    if ran < 5:
        print(f"FAIL: only {ran} commands found in {TUTORIAL}")
        return 1
    print(f"tutorial ok: {ran} commands")
    return 0


if __name__ == "__main__":
    sys.exit(main())
