#!/usr/bin/env python3
"""Mutates the shipped case files and checks that `mpile check` either accepts each mutant (exit 0)
or refuses it cleanly (exit 2 with one message that names the file), within a time and memory
bound, and never crashes, hangs or reports an internal error.

  tools/fuzz_cases.py --mutants 300                 # a seeded run, as the test suite does
  tools/fuzz_cases.py --mutants 100000 --seed 7     # a long run; failures are kept for replay
  tools/fuzz_cases.py --mutants 100000 --seed 7 --first 80000   # the same run's last 20 000
  tools/fuzz_cases.py --element-tests --mutants 200 # the element-test files, by `mpile element-test`

Each mutant applies one to three edits to a case file chosen at random: a number replaced by an
extreme or invalid one, a line deleted, duplicated or swapped, a key misspelt, a string value
replaced, bytes inserted, the file truncated, a deeply nested or very long value inserted. A
failing mutant is written to --keep with the command that shows it.
"""

import argparse
import concurrent.futures
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Cases whose check takes more than about half a second are left out of the default set: they add
# time, not kinds of input (their tables are those of the quick cases).
SLOW = {"cpt_r6.toml", "cpt_r8.toml"}

NUMBERS = ["0", "-0.0", "-1", "1e308", "-1e308", "1e-308", "5e-324", "nan", "inf", "-inf",
           "4294967304", "9223372036854775807", "-9223372036854775808", "1e9", "1e-9", "2", "0.5",
           "100000", "1e5", "0x10", "1_000", "+1", ".5", "1."]
STRINGS = ['""', '"x"', '"linear"', '"gimp"', '"axisymmetric"', '"plane_strain"', '"sand"', '"pile"',
           '"\\u0000"', '"' + "a" * 300 + '"', "true", "[]", "{}", "[1, 2, 3]", "{ a = 1 }"]
NUMBER = re.compile(r"(?<![\w.\"])[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+)(?![\w.\"])")
KEY = re.compile(r"^(\s*)([A-Za-z_][A-Za-z0-9_]*)(\s*=)", re.MULTILINE)
STRING = re.compile(r'"[^"\n]*"')


def mutate(text, rng):
    lines = text.split("\n")
    kind = rng.choice(["number", "number", "number", "delete", "duplicate", "swap", "key", "string",
                       "bytes", "truncate", "nest", "long"])
    if kind == "number":
        spans = [m.span() for m in NUMBER.finditer(text)]
        if spans:
            a, b = rng.choice(spans)
            return text[:a] + rng.choice(NUMBERS) + text[b:], kind
    if kind == "delete" and lines:
        del lines[rng.randrange(len(lines))]
        return "\n".join(lines), kind
    if kind == "duplicate" and lines:
        k = rng.randrange(len(lines))
        lines.insert(k, lines[k])
        return "\n".join(lines), kind
    if kind == "swap" and len(lines) > 1:
        a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[a], lines[b] = lines[b], lines[a]
        return "\n".join(lines), kind
    if kind == "key":
        spans = [m.span(2) for m in KEY.finditer(text)]
        if spans:
            a, b = rng.choice(spans)
            key = text[a:b]
            k = rng.randrange(len(key))
            edit = rng.choice([key[:k] + key[k + 1:], key[:k] + rng.choice("abcxyz_") + key[k:],
                               key + "s", key.upper()])
            return text[:a] + edit + text[b:], kind
    if kind == "string":
        spans = [m.span() for m in STRING.finditer(text)]
        if spans:
            a, b = rng.choice(spans)
            return text[:a] + rng.choice(STRINGS) + text[b:], kind
    if kind == "bytes":
        k = rng.randrange(len(text) + 1)
        junk = "".join(chr(rng.choice([0, 1, 9, 10, 13, 34, 39, 61, 91, 93, 123, 125, 0xFF, 0x7F,
                                       0xE9, 0x2028])) for _ in range(rng.randint(1, 4)))
        return text[:k] + junk + text[k:], kind
    if kind == "truncate":
        return text[:rng.randrange(len(text) + 1)], kind
    if kind == "nest":
        depth = rng.choice([10, 70, 1000])
        k = rng.randrange(len(lines) + 1)
        lines.insert(k, "nested = " + "[" * depth + "1" + "]" * depth)
        return "\n".join(lines), kind
    if kind == "long":
        k = rng.randrange(len(lines) + 1)
        lines.insert(k, "snapshot_times = [" + ", ".join(["0.1"] * rng.choice([10, 5000])) + "]")
        return "\n".join(lines), kind
    return text, "none"


def limits(memory_mib, cpu_seconds):
    def apply():
        if memory_mib > 0:
            resource.setrlimit(resource.RLIMIT_AS, (memory_mib << 20, memory_mib << 20))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds))
    return apply


def command(mpile, path):
    """How a mutant is read: a case with `mpile check`; a sweep file (cases/sweeps/) with
    `mpile sweep --prepare`, which reads it and every variant's case and writes the workflow; an
    element-test file (cases/element_tests/) with `mpile element-test`, which reads and runs it
    (its path at most 1e7 increments)."""
    folder = os.path.basename(os.path.dirname(path))
    if folder == "sweeps":
        return [mpile, "sweep", path, "--prepare", "--out", path + ".workflow"]
    if folder == "element_tests":
        return [mpile, "element-test", path, "--out", path + ".csv"]
    return [mpile, "check", path]


# A loaded machine slows a check without its doing more work: the time bound is on CPU seconds
# (the process is killed past it). A check that waits without computing (a FIFO read) is caught
# by the wall clock: past the bound, it fails once it has gone this long without using the CPU.
IDLE_SECONDS = 10.0


def cpu_seconds(pid):
    """User plus system CPU time of a process and its threads so far (s), or None once it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


def run_bounded(argv, timeout, memory_mib):
    """(returncode, stderr bytes), or None for a process that waited IDLE_SECONDS without computing
    after `timeout` s of wall time."""
    with subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          preexec_fn=limits(memory_mib, int(timeout))) as process:
        # stderr is read by a thread so that a long message cannot block the process.
        chunks = []
        reader = threading.Thread(target=lambda: chunks.append(process.stderr.read()))
        reader.start()
        start = time.monotonic()
        last_cpu, last_change = 0.0, start
        while True:
            try:
                process.wait(timeout=0.5)
                break
            except subprocess.TimeoutExpired:
                now = time.monotonic()
                cpu = cpu_seconds(process.pid)
                if cpu is not None and cpu > last_cpu:
                    last_cpu, last_change = cpu, now
                if now - start > timeout and now - last_change > IDLE_SECONDS:
                    process.kill()
                    process.wait()
                    reader.join()
                    return None
        reader.join()
        return process.returncode, b"".join(chunks)


def check(mpile, path, timeout, memory_mib):
    """One mutant read: ("accepted" | "refused" | "stopped", None), or ("failed", what went wrong)."""
    done = run_bounded(command(mpile, path), timeout, memory_mib)
    if done is None:
        return "failed", f"no answer: it waited {IDLE_SECONDS:g} s without computing"
    returncode, stderr = done
    err = stderr.decode("utf-8", "replace")
    if returncode == -signal.SIGXCPU or returncode == -signal.SIGKILL:
        return "failed", f"more than {int(timeout)} s of CPU time: {err.strip()[-300:]}"
    if returncode < 0:
        return "failed", f"killed by signal {-returncode}: {err.strip()[-300:]}"
    if returncode == 0:
        return "accepted", None
    # An element test runs its path: one the material cannot follow stops it with exit 1 and a
    # message naming the file, line and increment, as a run that goes wrong does; a check has no
    # such outcome.
    stopped = returncode == 1 and command(mpile, path)[1] == "element-test"
    if returncode != 2 and not stopped:
        return "failed", f"exit {returncode}: {err.strip()[-300:]}"
    # Notes (a one-cell wall, say) go before the refusal and may name an included file; the
    # refusal's first line names the file (a TOML syntax error then shows the line with a caret).
    lines = [line for line in err.splitlines()
             if line.strip() and not line.startswith("mpile: note: ")]
    if not lines or not lines[0].startswith("mpile: ") or "internal error" in err:
        return "failed", f"exit {returncode} without a message: {err.strip()[-300:]}"
    if os.path.basename(path) not in lines[0]:
        return "failed", f"exit {returncode} without naming the file: {lines[0][:300]}"
    return ("stopped" if stopped else "refused"), None


def draw_mutants(cases, seed, count, first=0):
    """Mutants first to count - 1 of the seeded sequence, as (index, (name, folder, text, edits)).
    The earlier ones are drawn too, so a run from `first` checks what a whole run would there."""
    rng = random.Random(seed)
    for i in range(count):
        name, folder, text = rng.choice(cases)
        edits = []
        for _ in range(rng.randint(1, 3)):
            text, kind = mutate(text, rng)
            edits.append(kind)
        if i >= first:
            yield i, (name, folder, text, edits)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mpile", default=os.path.join(ROOT, "build/release/bin/mpile"))
    parser.add_argument("--mutants", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--first", type=int, default=0,
                        help="check only the mutants from this index on (the earlier ones are still drawn, "
                             "so a long run cut short is finished with the same mutants)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--timeout", type=float, default=5.0,
                        help="CPU seconds one check may take (on the wall clock it may take longer "
                             "while it computes, and fails once it waits 10 s without computing)")
    parser.add_argument("--memory", type=int, default=1024,
                        help="MiB of address space per check (0: no limit, for sanitizer builds)")
    parser.add_argument("--budget", type=int, default=0,
                        help="MiB a case may need (MPILE_MEMORY_BUDGET_MIB), for sanitizer builds "
                             "whose address space cannot be limited: 768 refuses what --memory "
                             "1024 does (0: none)")
    parser.add_argument("--all-cases", action="store_true", help="include the slow case files")
    parser.add_argument("--element-tests", action="store_true",
                        help="mutate the element-test files (cases/element_tests/) instead of the "
                             "cases")
    parser.add_argument("--keep", default=os.path.join(tempfile.gettempdir(), "mpile-fuzz-failures"))
    args = parser.parse_args()
    if args.budget > 0:
        os.environ["MPILE_MEMORY_BUDGET_MIB"] = str(args.budget)  # the checks inherit it
    if not 0 <= args.first < args.mutants:
        parser.error(f"--first must be at least 0 and below --mutants ({args.mutants})")

    cases = []
    for directory, _, files in os.walk(os.path.join(ROOT, "cases")):
        if (os.path.basename(directory) == "element_tests") != args.element_tests:
            continue  # element-test files, or cases
        if os.path.basename(directory) == "base":
            continue  # parts of cases, read through the cases that name them
        for name in sorted(files):
            if name.endswith(".toml") and (args.all_cases or name not in SLOW):
                with open(os.path.join(directory, name), encoding="utf-8") as f:
                    folder = os.path.relpath(directory, os.path.join(ROOT, "cases"))
                    cases.append((name, folder, f.read()))
    cases.sort()
    work = tempfile.mkdtemp(prefix="mpile-fuzz-")
    # A mutant sits where its case does among copies of all the shipped files, so that a base
    # (`base = "base/..."`) and a sweep's case (`case = "../monopile/..."`) resolve.
    shutil.copytree(os.path.join(ROOT, "cases"), work, dirs_exist_ok=True)
    jobs = []
    for i, (name, folder, text, edits) in draw_mutants(cases, args.seed, args.mutants, args.first):
        os.makedirs(os.path.join(work, folder), exist_ok=True)
        path = os.path.join(work, folder, f"m{i:06d}_{name}")
        with open(path, "w", encoding="utf-8", errors="surrogatepass") as f:
            f.write(text)
        jobs.append((path, name, edits))

    start = time.monotonic()
    failures = []

    def keep(path, name, edits, problem):
        """A failure is kept and said at once, so that a long run cut short loses none."""
        if not os.path.isdir(os.path.join(args.keep, "monopile")):
            os.makedirs(args.keep, exist_ok=True)
            shutil.copytree(os.path.join(ROOT, "cases"), args.keep, dirs_exist_ok=True)
        kept = os.path.join(args.keep, os.path.relpath(path, work))
        os.makedirs(os.path.dirname(kept), exist_ok=True)
        shutil.copyfile(path, kept)
        print(f"FAIL {kept} ({name}; {', '.join(edits)}): {problem}")
        print(f"     replay: {' '.join(command(args.mpile, kept))}", flush=True)

    counts = {"accepted": 0, "refused": 0, "stopped": 0, "failed": 0}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        outcomes = pool.map(lambda job: check(args.mpile, job[0], args.timeout, args.memory), jobs)
        for done, ((path, name, edits), (outcome, problem)) in enumerate(zip(jobs, outcomes), 1):
            counts[outcome] += 1
            if problem is not None:
                failures.append((path, name, edits, problem))
                keep(path, name, edits, problem)
            if (args.first + done) % 10000 == 0 and done < len(jobs):
                # A long run says where it is, so that one cut short still has counts.
                print(f"{args.first + done} of {args.mutants} mutants in {time.monotonic() - start:.0f} s: "
                      f"{counts['accepted']} accepted, {counts['refused']} refused, "
                      f"{len(failures)} failures so far", flush=True)
    elapsed = time.monotonic() - start
    print(f"{len(jobs)} mutants (from {args.first} to {args.mutants - 1}) of {len(cases)} {'element-test' if args.element_tests else 'case'} files (seed {args.seed}) in {elapsed:.0f} s: "
          f"{counts['accepted']} accepted, {counts['refused']} refused, "
          + (f"{counts['stopped']} stopped, " if args.element_tests else "")
          + f"{len(failures)} failures")
    shutil.rmtree(work)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
