#!/usr/bin/python3
"""How good `mpile check --pilot` is: for each case, the run time a pilot estimates, then the run's
own wall time, printed as rows of the table in docs/performance.md ("Run-time estimates").

  tools/estimate_table.py cases/verification/*.toml cases/monopile/gdp_quick.toml --pilot 10
  tools/estimate_table.py cases/monopile/gdp_paper.toml --pilot 60 --out /tmp/estimates

Runs one case at a time (a shared machine makes both numbers wrong); --no-run prints the estimate
only. The runs' outputs go under --out.
"""
import argparse
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def estimate(mpile, case, pilot, threads):
    """((low, high) estimate in s, or None; the pilot's note when it could not see a whole drive
    period). low == high where the pilot gives one number."""
    done = subprocess.run([mpile, "check", case, "--pilot", str(pilot), "--threads", str(threads)],
                          capture_output=True, text=True)
    found = re.search(r"^estimated run time: (at most )?(?:([0-9.e+]+) to )?([0-9.e+]+) s", done.stdout,
                      re.MULTILINE)
    if done.returncode != 0 or not found:
        last = (done.stderr.strip().splitlines() or ["no estimate"])[-1]
        return None, f"no estimate: {last[:120]}"
    note = "flagged: within the drive's first period" if "covers one period" in done.stdout else ""
    if found.group(1):
        note = (note + "; " if note else "") + "a bound (at most)"
    high = float(found.group(3))
    return (float(found.group(2)) if found.group(2) else high, high), note


def shown(value, form=".3g"):
    low, high = value
    return f"{high:{form}}" if low == high else f"{low:{form}} to {high:{form}}"


def run(mpile, case, out, threads):
    start = time.monotonic()
    done = subprocess.run([mpile, "run", case, "--out", out, "--threads", str(threads)],
                          capture_output=True, text=True)
    return time.monotonic() - start, done.returncode


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cases", nargs="+")
    parser.add_argument("--mpile", default=os.path.join(ROOT, "build/release/bin/mpile"))
    parser.add_argument("--pilot", type=float, default=10.0, help="s of wall time for each pilot")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--no-run", action="store_true", help="the estimates only")
    parser.add_argument("--out", default=os.path.join("out", "estimates"))
    args = parser.parse_args()
    print("| case | pilot (s) | estimate (s) | run (s) | estimate / run |")
    print("|---|---|---|---|---|")
    for case in args.cases:
        name = os.path.relpath(os.path.abspath(case), os.path.join(ROOT, "cases"))
        value, note = estimate(args.mpile, case, args.pilot, args.threads)
        text = shown(value) if value is not None else ""
        if note:
            text = f"{text}, {note}" if text else note
        if args.no_run:
            print(f"| `{name[:-5]}` | {args.pilot:g} | {text} | | |", flush=True)
            continue
        wall, status = run(args.mpile, case, os.path.join(args.out, os.path.basename(case)[:-5]), args.threads)
        ran = f"{wall:.3g}" + ("" if status == 0 else f" (exit {status})")
        ratio = ""
        if value is not None and wall > 0:
            ratio = shown((value[0] / wall, value[1] / wall), ".2f")
        print(f"| `{name[:-5]}` | {args.pilot:g} | {text} | {ran} | {ratio} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
