#!/usr/bin/python3
"""How right the progress line's ETA is: runs `mpile run` on a terminal (a pseudo-terminal, so the
line is redrawn every 0.25 s as a user sees it), takes each line as it is drawn, and compares its
ETA with the wall time its phase actually went on for after it.

  tools/progress_error.py --mpile build/release/bin/mpile cases/monopile/gdp_quick.toml [-- RUN OPTIONS]

Prints one row per line drawn (wall time, phase, the ETA shown, the time the phase really had left,
their ratio) and, per phase, the ratio at its first line, 5 s into the run, and the largest. An ETA
shown as a bound ("ETA <= 464 s") is counted as its number and marked as a bound.
"""
import argparse
import math
import os
import pty
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("case")
parser.add_argument("--mpile", default="build/release/bin/mpile")
parser.add_argument("--out", help="output directory of the run (default: a temporary one)")
parser.add_argument("--quiet", action="store_true", help="print the summary only")
parser.add_argument("run_options", nargs="*", help="more options for mpile run (after --)")
args = parser.parse_args()

out = args.out or tempfile.mkdtemp(prefix="progress-error-")
master, slave = pty.openpty()
start = time.monotonic()
process = subprocess.Popen([args.mpile, "run", args.case, "--out", out] + args.run_options,
                           stdin=subprocess.DEVNULL, stdout=slave, stderr=slave, close_fds=True)
os.close(slave)
events = []  # (wall, text) of each line drawn or written
buffer = b""
while True:
    ready, _, _ = select.select([master], [], [], 0.5)
    if ready:
        try:
            data = os.read(master, 65536)
        except OSError:
            data = b""
        if not data:
            break
        now = time.monotonic() - start
        buffer += data
        parts = re.split(rb"[\r\n]", buffer)
        buffer = parts.pop()
        for part in parts:
            text = part.replace(b"\x1b[K", b"").decode(errors="replace").strip()
            if text:
                events.append((now, text))
    elif process.poll() is not None:
        break
process.wait()
end = time.monotonic() - start
if not args.out:
    shutil.rmtree(out, ignore_errors=True)

progress = re.compile(r"^(\S+) = (\S+) of (\S+) (\S+)  \[(.+?)\]  (\d+) steps/s  ETA (<= )?([^ ]+)(?: to ([^ ]+))?")
ended = re.compile(r"phase (.+?) ended at t = ")
phase_end = {}
for wall, text in events:
    m = ended.search(text)
    if m:
        phase_end[m.group(1)] = wall
rows = []
for wall, text in events:
    m = progress.match(text)
    if not m:
        continue
    phase = m.group(5)
    bound = m.group(7) is not None
    low = float("inf") if m.group(8) == "-" else float(m.group(8))
    high = float(m.group(9)) if m.group(9) else low
    left = phase_end.get(phase, end) - wall
    rows.append((wall, phase, low, high, bound, left))



def shown(row):
    wall, phase, low, high, bound, left = row
    return ("<= " if bound else "") + (f"{low:.0f}" if low == high else f"{low:.0f} to {high:.0f}")


def ratio(row):
    """The ETA over the time really left: the nearer end of a range, 1 when inside it."""
    wall, phase, low, high, bound, left = row
    if left <= 0:
        return float("nan")
    if low <= left <= high:
        return 1.0
    return (low if left < low else high) / left


if not args.quiet:
    print(f"{'wall s':>8} {'phase':<14} {'ETA s':>12} {'left s':>8} {'ratio':>7}")
    for row in rows:
        print(f"{row[0]:8.2f} {row[1]:<14} {shown(row):>12} {row[5]:8.2f} {ratio(row):7.2f}")
print(f"{args.case}: exit status {process.returncode}, {end:.1f} s of wall time, {len(rows)} progress lines")
for phase in dict.fromkeys(r[1] for r in rows):
    mine = [r for r in rows if r[1] == phase]
    estimates = [r for r in mine if not r[4] and r[5] >= 1.0]
    first = mine[0]
    text = (f"  {phase}: ended {phase_end.get(phase, end):.1f} s into the run; first line at {first[0]:.2f} s: "
            f"ETA {shown(first)} s for {first[5]:.2f} s left")
    at5 = next((r for r in rows if r[0] >= 5.0), None)
    if at5 is not None and at5[1] == phase:
        text += f"; at {at5[0]:.1f} s: ETA {shown(at5)} s for {at5[5]:.1f} s (x {ratio(at5):.2f})"
    if estimates:
        first_estimate = estimates[0]
        worst = max(estimates, key=lambda r: abs(math.log(ratio(r))))
        text += (f"; first estimate at {first_estimate[0]:.2f} s: ETA {shown(first_estimate)} s for "
                 f"{first_estimate[5]:.1f} s (x {ratio(first_estimate):.2f}); furthest estimate (1 s or more "
                 f"left): x {ratio(worst):.2f} at {worst[0]:.2f} s")
    print(text)
sys.exit(process.returncode)
