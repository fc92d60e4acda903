"""Cases built, run and swept from Python, with the checks of the command line.

A `Case` is a case file and a list of `--set key.path=value` assignments, exactly what
`mpile run CASE --set ...` takes. Every assignment is checked when it is made by the mpile program
itself (`mpile check CASE --set ...`), so a misspelt key or a value out of range is refused with
mpile's own `file:line: key: reason`, as on the command line:

    import mpile
    case = mpile.Case.read("cases/monopile/jacked_quick.toml")
    case["monopile.friction"] = 0.3                      # --set monopile.friction=0.3, checked now
    case.set("phases.installation.duration", 0.5)
    case.write("friction_03.toml")                        # a case file mpile run reads as this case
    run = case.run("out/friction_03", threads=2, progress=True)
    run.history()                                          # mpile.open_history("out/friction_03")

Python values become TOML values (bool, int, float, str, lists and dicts of them; floats by
`repr`, so that they reach mpile exactly). `run_sweep` runs a list of such cases through
`mpile sweep` (Snakemake) and gathers them into one table (docs/sweeps.md).

The program is found from the `mpile` argument, else the MPILE environment variable, else `mpile`
on PATH, else the build beside this package in a source tree (build/release/bin/mpile).
"""
import itertools
import math
import numbers
import os
import queue
import re
import shutil
import signal
import subprocess
import threading
import time
import tomllib
import warnings
from pathlib import Path



class CaseError(ValueError):
    """A case, a key or a value mpile refuses (its exit status 2). The message is mpile's own
    (`file:line: key: reason`, or `--set key:1: key: reason` for a value set from Python);
    `status` is mpile's exit status and `output` all it printed on stderr."""

    def __init__(self, message, status=2, output=""):
        super().__init__(message)
        self.status = status
        self.output = output


class RunError(RuntimeError):
    """A run that started but failed (mpile's exit status 1: an instability, a particle leaving
    the grid, ...) or was interrupted. The message is mpile's; `run` is the `Run`, whose history
    holds the rows written until then, `status` the exit status and `output` mpile's stderr."""

    def __init__(self, message, run=None, status=1, output=""):
        super().__init__(message)
        self.run = run
        self.status = status
        self.output = output


class MpileNotFoundError(FileNotFoundError):
    """No mpile program where it was looked for."""


class CaseWarning(UserWarning):
    """A plausibility warning mpile prints for a case (a value most likely in the wrong unit)."""


# The build of a source tree, python/mpile/../../build/release/bin/mpile.
_SOURCE_TREE_BUILD = Path(__file__).resolve().parent.parent.parent / "build" / "release" / "bin" / "mpile"


def find_mpile(mpile=None):
    """The path of the mpile program: `mpile` (a path, or a name looked up on PATH), else $MPILE,
    else `mpile` on PATH, else build/release/bin/mpile of the source tree this package is in.
    Raises MpileNotFoundError saying where it looked."""
    def executable(path):
        return os.path.isfile(path) and os.access(path, os.X_OK)

    for given, origin in ((mpile, "the mpile argument"), (os.environ.get("MPILE"), "MPILE")):
        if given:
            given = os.fspath(given)
            found = given if executable(given) else (shutil.which(given) if os.sep not in given else None)
            if not found:
                raise MpileNotFoundError(f"{origin} names {given!r}, which is not an executable file")
            return str(Path(found).absolute())
    found = shutil.which("mpile")
    if found:
        return str(Path(found).absolute())
    if executable(_SOURCE_TREE_BUILD):
        return str(_SOURCE_TREE_BUILD)
    raise MpileNotFoundError("no mpile program: pass mpile=PATH, set the MPILE environment variable to "
                             "its path, or put it on PATH (a build writes it to build/release/bin/mpile)")


# TOML values from Python values ------------------------------------------------------------------

_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+\Z")


def toml_string(text):
    """`text` as a TOML basic string: quoted, with quotes, backslashes and control characters
    escaped (one line, as a --set value must be)."""
    out = ['"']
    for character in text:
        code = ord(character)
        if character in _ESCAPES:
            out.append(_ESCAPES[character])
        elif code < 0x20 or code == 0x7F:
            out.append(f"\\u{code:04X}")
        elif 0xD800 <= code <= 0xDFFF:
            raise CaseError(f"{text!r} holds a lone surrogate (U+{code:04X}), which TOML text cannot hold")
        else:
            out.append(character)
    out.append('"')
    return "".join(out)


def toml_key(key):
    """A TOML key: bare when it can be, else quoted."""
    return key if _BARE_KEY.match(key) else toml_string(key)


def toml_value(value):
    """The TOML text of one value, as `--set key=VALUE` and a case file take it: bool, int, float
    (by repr, which reads back as the same double; nan, inf and -inf as TOML spells them), str,
    a list or tuple of values (an array), a dict of them (an inline table). numpy scalars and
    arrays count as the Python values they hold. Raises TypeError for anything else (TOML has no
    null)."""
    if hasattr(value, "tolist") and hasattr(value, "dtype"):  # a numpy scalar or array
        value = value.tolist()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        items = []
        for key, element in value.items():
            if not isinstance(key, str):
                raise TypeError(f"a TOML table's keys are strings, not {type(key).__name__} ({key!r})")
            items.append(f"{toml_key(key)} = {toml_value(element)}")
        return "{" + ", ".join(items) + "}"
    raise TypeError(f"{value!r} ({type(value).__name__}) has no TOML value: give a bool, int, float, "
                    "str, or a list or dict of them")


# Running the program -----------------------------------------------------------------------------

def _execute(command, progress=None, timeout=None):
    """Runs `command`, returns (exit status, stdout, stderr). Lines are passed to `progress` as
    they come (True prints them; a callable is called with each line, in this thread). After
    `timeout` seconds the program gets SIGTERM and subprocess.TimeoutExpired is raised. Ctrl-C
    (KeyboardInterrupt) is passed on to the program as SIGINT, which then writes its checkpoint
    and stops; the KeyboardInterrupt is raised once it has. The program runs in a session of its
    own, so that a terminal's Ctrl-C reaches it once, through here."""
    if progress is True:
        def progress(line):
            print(line, flush=True)

    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               errors="replace", start_new_session=True)
    lines = queue.Queue()
    collected = {"stdout": [], "stderr": []}

    def pump(stream, name):
        for line in stream:
            lines.put((name, line))
        lines.put((name, None))

    readers = [threading.Thread(target=pump, args=(process.stdout, "stdout"), daemon=True),
               threading.Thread(target=pump, args=(process.stderr, "stderr"), daemon=True)]
    for reader in readers:
        reader.start()
    open_streams = 2
    deadline = None if timeout is None else time.monotonic() + timeout
    try:
        while open_streams:
            try:
                left = None if deadline is None else max(0.0, deadline - time.monotonic())
                name, line = lines.get(timeout=left)
            except queue.Empty:
                process.send_signal(signal.SIGTERM)  # mpile writes its checkpoint and stops
                process.wait()
                raise subprocess.TimeoutExpired(command, timeout) from None
            if line is None:
                open_streams -= 1
                continue
            collected[name].append(line)
            if progress:
                progress(line.rstrip("\n"))
        process.wait()
    except BaseException as error:
        # Ctrl-C, or a progress callable that raised: the program stops as it does on Ctrl-C or
        # SIGTERM (with a checkpoint), and is killed if it has not within two minutes.
        if process.poll() is None:
            process.send_signal(signal.SIGINT if isinstance(error, KeyboardInterrupt) else signal.SIGTERM)
            try:
                process.wait(timeout=120)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        raise
    finally:
        for reader in readers:
            reader.join(timeout=5)
    return process.returncode, "".join(collected["stdout"]), "".join(collected["stderr"])


def _notes_out(stderr):
    """mpile's stderr without its notes and plausibility warnings (which come before an error)."""
    return [line for line in stderr.splitlines() if not line.startswith(("mpile: note:", "mpile: warning:"))]


def _refusal(stderr):
    """The message of mpile's exit status 2: what it printed, less notes, warnings and 'mpile: '."""
    text = "\n".join(_notes_out(stderr)).strip()
    return text[len("mpile: "):] if text.startswith("mpile: ") else text or "mpile refused the case"


def _failure(stderr):
    """The message of a failed run: mpile's last 'mpile: ' line and what follows it."""
    lines = _notes_out(stderr)
    starts = [k for k, line in enumerate(lines) if line.startswith("mpile: ")]
    text = "\n".join(lines[starts[-1]:] if starts else lines[-10:]).strip()
    return text[len("mpile: "):] if text.startswith("mpile: ") else text or "the run failed"


def _warn(stderr):
    for line in stderr.splitlines():
        if line.startswith("mpile: warning: "):
            warnings.warn(line[len("mpile: warning: "):], CaseWarning, stacklevel=4)


class Case:
    """A case file and `--set` assignments: what `mpile run CASE --set key=value ...` runs.

    `Case(path)` takes the file as it is, unchecked; `Case.read(path)` checks it with
    `mpile check` first. `case[key] = value` (or `case.set(key, value)`) adds `--set key=value`,
    the value a Python value turned into TOML (`toml_value`), and checks the whole case at once:
    a key or value mpile refuses raises CaseError with mpile's message and leaves the case as it
    was. Setting a key again replaces its earlier assignment. `case[key]` reads a value of the case
    as mpile resolves it (bases merged, values set; keys left to their defaults are not there).
    """

    def __init__(self, path, overrides=(), mpile=None, strict=False):
        self.path = Path(path).absolute()
        self.strict = bool(strict)
        self._mpile = os.fspath(mpile) if mpile is not None else None
        self._sets = []
        for assignment in [overrides] if isinstance(overrides, str) else overrides:
            key, equals, text = assignment.partition("=")
            if not equals:
                raise CaseError(f"--set {assignment}: expected key.path=value")
            self._sets.append((key.strip(), text))
        self._resolved = None

    @classmethod
    def read(cls, path, overrides=(), mpile=None, strict=False):
        """The case file at `path` (with `overrides`, "key.path=value" strings as --set takes them),
        checked by `mpile check`: CaseError with mpile's message if it refuses it."""
        case = cls(path, overrides, mpile=mpile, strict=strict)
        case.check()
        return case

    @property
    def mpile(self):
        """The mpile program this case is checked and run with (found by `find_mpile`)."""
        self._mpile = find_mpile(self._mpile)
        return self._mpile

    @property
    def overrides(self):
        """The assignments, "key.path=value" as `--set` takes them, in the order they apply."""
        return [f"{key}={text}" for key, text in self._sets]

    def _arguments(self):
        arguments = [str(self.path)]
        for assignment in self.overrides:
            arguments += ["--set", assignment]
        return arguments + (["--strict"] if self.strict else [])

    def __repr__(self):
        return f"Case({str(self.path)!r}, overrides={self.overrides!r})"

    def copy(self):
        """Another Case of the same file and assignments, changed independently of this one."""
        other = Case(self.path, self.overrides, mpile=self._mpile, strict=self.strict)
        other._resolved = self._resolved
        return other

    def check(self):
        """Checks the case with `mpile check` and returns what it prints (the grid, particles,
        phases and estimated cost). Raises CaseError with mpile's message if it is refused;
        plausibility warnings (a value most likely in the wrong unit) become CaseWarnings."""
        status, stdout, stderr = _execute([self.mpile, "check", *self._arguments(), "--threads", "1"])
        if status == 2:
            raise CaseError(_refusal(stderr), status, stderr)
        if status != 0:
            raise RunError(f"mpile check {self.path} ended with exit status {status}:\n{_failure(stderr)}",
                           status=status, output=stderr)
        _warn(stderr)
        return stdout

    def set(self, key, value, check=True):
        """Sets `key` (a key path as `--set` takes it: `monopile.friction`, `phases.1.duration`,
        `phases.installation.duration`) to `value` and, with `check`, checks the case with mpile:
        CaseError with mpile's message if it refuses the key or value, the case then unchanged.
        With check=False the check is left to `check()` or `run()` (fifty sets, one check).
        Returns the case, so that sets chain."""
        return self.update({key: value}, check=check)

    def update(self, values, check=True):
        """Sets every key of the dict `values` (in its order), then checks once (see `set`)."""
        before = list(self._sets)
        for key, value in values.items():
            if not isinstance(key, str) or not key.strip() or "=" in key or "\n" in key:
                self._sets = before
                raise CaseError(f"--set {key!r}: not a key path (keys joined by dots, like monopile.friction)")
            key = key.strip()
            try:
                text = toml_value(value)
            except (TypeError, CaseError):
                self._sets = before
                raise
            self._sets = [(k, t) for k, t in self._sets if k != key] + [(key, text)]
        self._resolved = None
        if check:
            try:
                self.check()
            except CaseError:
                self._sets = before
                raise
        return self

    def __setitem__(self, key, value):
        self.set(key, value)

    def unset(self, key):
        """Removes the assignment of `key` (the case file's value applies again)."""
        if all(k != key for k, _ in self._sets):
            raise KeyError(f"{key} is not set (set: {', '.join(k for k, _ in self._sets) or 'nothing'})")
        self._sets = [(k, t) for k, t in self._sets if k != key]
        self._resolved = None

    def __delitem__(self, key):
        self.unset(key)

    def resolved_text(self):
        """The case as mpile resolves it (bases merged, values set), as TOML text: what the
        history's `case_resolved` of a run of it holds (`mpile check CASE --set ...
        --print-resolved`)."""
        key = (tuple(self._sets), self.path.stat().st_mtime_ns if self.path.exists() else None)
        if self._resolved is None or self._resolved[0] != key:
            status, stdout, stderr = _execute([self.mpile, "check", *self._arguments(), "--threads", "1",
                                               "--print-resolved"])
            if status == 2:
                raise CaseError(_refusal(stderr), status, stderr)
            if status != 0:
                raise RunError(f"mpile could not resolve {self.path} (exit status {status}):\n"
                               + _failure(stderr), status=status, output=stderr)
            # The title a run takes: the case's, else its file's name (docs/case-format.md).
            self._resolved = (key, stdout, tomllib.loads(stdout).get("title", self.path.stem))
        return self._resolved[1]

    def resolved(self):
        """The resolved case (`resolved_text`) parsed: a dict."""
        return tomllib.loads(self.resolved_text())

    def __getitem__(self, key):
        node = self.resolved()
        for part in key.split("."):
            if isinstance(node, dict) and part in node:
                node = node[part]
            elif isinstance(node, list) and part.isdigit() and int(part) < len(node):
                node = node[int(part)]
            elif isinstance(node, list) and any(isinstance(e, dict) and e.get("name") == part for e in node):
                node = next(e for e in node if isinstance(e, dict) and e.get("name") == part)
            else:
                raise KeyError(f"{key}: the case as resolved has no {part!r} there (a key left to its "
                               "default is not in it)")
        return node

    def write(self, path):
        """Writes a case file that is this case: the case as mpile resolves it (`resolved_text`:
        bases merged, values set, so it stands alone wherever it is written), the original file
        and the assignments in a comment at its top, and the title the run would have (a case
        without one is titled by its file's name). Checked with `mpile check`; returns its path."""
        path = Path(path)
        text = self.resolved_text()
        title = self._resolved[2]
        lines = [f"# {self.path}"] + [f"#   --set {assignment}" for assignment in self.overrides]
        lines.append("# written by mpile.Case.write: the case as mpile resolves it (bases merged, values set)")
        if title and "title" not in tomllib.loads(text):
            lines.append(f"title = {toml_string(title)}")
        path.write_text("\n".join(lines) + "\n" + text, encoding="utf-8")
        Case(path, mpile=self._mpile, strict=self.strict).check()
        return path

    def run(self, out, threads=1, progress=False, stop_after=None, resume=False, restart=None, timeout=None):
        """Runs the case: `mpile run CASE --set ... --out OUT --threads THREADS`. Returns a `Run`.

        progress: True prints mpile's lines as they come (the phases, a progress line every 5 s,
        the summary); a callable gets each line. stop_after: stop after that many steps as if
        interrupted, with a checkpoint (the Run's status is then "interrupted at t = ... s"). resume: mpile's
        --continue (continue a run in OUT that stopped before its end, leave a complete one alone).
        restart: a checkpoint to continue from (--restart). Ctrl-C stops mpile with a checkpoint.

        Raises CaseError (exit status 2: a case mpile refuses) or RunError (exit status 1: the run
        failed, e.g. went unstable; or interrupted), each with mpile's message."""
        out = Path(out).absolute()
        command = [self.mpile, "run", *self._arguments(), "--out", str(out), "--threads", str(int(threads))]
        if stop_after is not None:
            command += ["--stop-after", str(int(stop_after))]
        if resume:
            command.append("--continue")
        if restart is not None:
            command += ["--restart", os.fspath(restart)]
        status, stdout, stderr = _execute(command, progress, timeout)
        run = Run(out, self.copy(), stdout + stderr)
        if status == 0 or (status == 130 and stop_after is not None):
            _warn(stderr)
            return run
        if status == 2:
            raise CaseError(_refusal(stderr), status, stderr)
        raise RunError(_failure(stderr), run, status, stderr)


class Run(os.PathLike):
    """The output directory of one run (a path-like: `mpile.open_history(run)` works), with its
    readers: `history()`, `phases()`, `snapshots()`, `installation()`, `attributes()`."""

    def __init__(self, directory, case=None, output=""):
        self.directory = Path(directory)
        self.case = case
        self.output = output  # what mpile printed, stdout then stderr

    def __fspath__(self):
        return str(self.directory)

    def __repr__(self):
        return f"Run({str(self.directory)!r})"

    @property
    def status(self):
        """The history's status: "complete", "interrupted", "failed: ...", ..."""
        return self.attributes().get("status", "")

    def attributes(self):
        from .history import attributes

        return attributes(self.directory)

    def history(self, form="xarray"):
        from .history import open_history

        return open_history(self.directory, form=form)

    def phases(self):
        from .phase_table import phases

        return phases(self.directory)

    def snapshots(self):
        from .snapshots import open_snapshots

        return open_snapshots(self.directory)

    def installation(self, **options):
        from .monopile import installation

        return installation(self.directory, **options)


# Sweeps ------------------------------------------------------------------------------------------

class SweepRun(os.PathLike):
    """A sweep's output directory (a path-like: `mpile.open_sweep(study)` works): `results()` is
    its table, `variants[i]` the variant id of the i-th case given and `run(i)` that case's Run."""

    def __init__(self, directory, cases, variants, output=""):
        self.directory = Path(directory)
        self.cases = list(cases)
        self.variants = list(variants)
        self.output = output

    def __fspath__(self):
        return str(self.directory)

    def __repr__(self):
        return f"SweepRun({str(self.directory)!r}, {len(self.cases)} cases)"

    def results(self, form="xarray"):
        """The gathered table: mpile.open_sweep(directory, form) (one row per variant, in the
        sweep's order: the parameters' values in the order the cases first give them, the first
        parameter slowest)."""
        from .sweep import open_sweep

        return open_sweep(self.directory, form=form)

    def run(self, index):
        """The Run of the `index`-th case given."""
        return Run(self.directory / "variants" / self.variants[index], self.cases[index])


def _as_parameters(cases):
    """(common assignments, {key: [value texts]}, per case its tuple of value indices) of cases of
    one file whose assignments differ in some keys, every combination of their values once."""
    first = cases[0]
    for number, case in enumerate(cases):
        if case.path != first.path:
            raise ValueError(f"a sweep runs one case file: case {number} is {case.path}, case 0 {first.path}")
    settings = [dict(case._sets) for case in cases]
    keys = list(dict.fromkeys(key for s in settings for key in s))
    for key in keys:
        missing = [n for n, s in enumerate(settings) if key not in s]
        if missing:
            raise ValueError(f"{key} is set in some cases and not in case {missing[0]}: a sweep sets a key "
                             "in every variant (set it there to the case file's value)")
    varying = [key for key in keys if len({s[key] for s in settings}) > 1]
    common = [f"{key}={text}" for key, text in first._sets if key not in varying]
    if not varying:
        raise ValueError("the cases do not differ: a sweep needs at least one key set to different values "
                         "(run a single case with Case.run)")
    values = {key: list(dict.fromkeys(s[key] for s in settings)) for key in varying}
    indices = [tuple(values[key].index(s[key]) for key in varying) for s in settings]
    seen = {}
    for number, index in enumerate(indices):
        if index in seen:
            raise ValueError(f"cases {seen[index]} and {number} are the same variant")
        seen[index] = number
    for combination in itertools.product(*(range(len(values[key])) for key in varying)):
        if combination not in seen:
            missing = ", ".join(f"{key} = {values[key][k]}" for key, k in zip(varying, combination))
            raise ValueError(f"the cases are not every combination of their values ({missing} is not among "
                             "them): mpile sweep runs a product of values; run other sets of cases one by "
                             "one with Case.run")
    return common, values, indices


def sweep_file_text(cases, title=None, threads=1, gather=()):
    """The text of the sweep file (docs/sweeps.md) that runs `cases`, and per case its position
    in the sweep's order. The cases are of one case file; their assignments common to all are the
    sweep's `set`, those that differ its parameters, whose values the cases must give in every
    combination (a grid; a single varying key is any list of distinct values)."""
    cases = list(cases)
    if not cases:
        raise ValueError("no cases to sweep")
    common, values, indices = _as_parameters(cases)
    lines = [f"title = {toml_string(title or cases[0].path.stem + ' from Python')}",
             f"case = {toml_string(str(cases[0].path))}",
             f"threads = {int(threads)}",
             "set = [" + ", ".join(toml_string(s) for s in common) + "]",
             "",
             "[parameters]"]
    lines += [f"{toml_string(key)} = [{', '.join(texts)}]" for key, texts in values.items()]
    for spec in gather:
        lines += ["", "[[gather]]"] + [f"{toml_key(k)} = {toml_value(v)}" for k, v in spec.items()]
    sizes = [len(texts) for texts in values.values()]
    positions = []
    for index in indices:
        position = 0
        for k, size in zip(index, sizes):
            position = position * size + k
        positions.append(position)
    return "\n".join(lines) + "\n", positions


def run_sweep(cases, out, gather=(), title=None, threads=1, cores=None, progress=False, strict=False,
              profile=None, prepare=False, mpile=None, timeout=None):
    """Runs `cases` (Cases of one case file) through `mpile sweep` into the directory `out` and
    returns a SweepRun (`.results()` the table, `.run(i)` the i-th case's run).

    The cases' assignments common to all become the sweep's `set`, those that differ its
    parameters: the cases must be every combination of the values they give (one varying key:
    any distinct values). `gather` is a list of dicts, each a [[gather]] table of the sweep file
    (name, series, and at_penetration with body, at_time or reduce; docs/sweeps.md). `threads`
    per run, `cores` to fill (default: all), `profile` a Snakemake profile (a cluster); with
    `prepare`, the workflow is written and its Snakemake command printed (`output`), nothing run.
    The sweep file is written to OUT/study.toml; running it again runs only the variants not
    finished.

    Raises ValueError for cases that are no product, CaseError where mpile refuses the sweep or
    a variant (exit status 2). Variants that fail do not stop the others: mpile's report of them
    is given as a RuntimeWarning and their rows' status says so."""
    cases = list(cases)
    text, positions = sweep_file_text(cases, title=title, threads=threads, gather=gather)
    out = Path(out).absolute()
    out.mkdir(parents=True, exist_ok=True)
    study = out / "study.toml"
    study.write_text(text, encoding="utf-8")
    command = [find_mpile(mpile if mpile is not None else cases[0]._mpile), "sweep", str(study), "--out", str(out)]
    if cores is not None:
        command += ["--cores", str(int(cores))]
    if profile is not None:
        command += ["--profile", os.fspath(profile)]
    if strict or any(case.strict for case in cases):
        command.append("--strict")
    if prepare:
        command.append("--prepare")
    status, stdout, stderr = _execute(command, progress, timeout)
    if status == 2:
        raise CaseError(_refusal(stderr), status, stderr)
    if status not in (0, 1) or not (prepare or (out / "results.csv").is_file()):
        raise RunError(f"mpile sweep ended with exit status {status}:\n{_failure(stderr)}", status=status,
                       output=stderr)
    with open(out / "sweep.toml", "rb") as f:
        expanded = tomllib.load(f)["variants"]
    if status == 1:
        warnings.warn(_failure(stderr), RuntimeWarning, stacklevel=2)
    return SweepRun(out, cases, [expanded[p]["id"] for p in positions], stdout + stderr)
