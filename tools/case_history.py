"""What the closed-form tools (tools/mandel.py, tools/barron.py) read from and write into case
files alike: the coupled soil a closed form is for, a case's time function as a piecewise-linear
history and its integral, a Python value as TOML text, and the repository's Python package."""
import pathlib
import sys

import numpy as np


def coupled_soil(case):
    """(name, material table, soil body) of a case's one coupled, linear elastic material and the
    one deformable body made of it: what the closed forms are for."""
    materials = case["materials"]
    coupled = [name for name, m in materials.items() if m.get("drainage") == "coupled"]
    if len(coupled) != 1:
        raise ValueError(f"one coupled material expected, found {coupled}")
    name = coupled[0]
    m = materials[name]
    if m.get("type") != "linear_elastic":
        raise ValueError(f"materials.{name}: the closed forms are for a linear elastic skeleton")
    bodies = [b for b in case["bodies"] if b["material"] == name and "rigid" not in b]
    if len(bodies) != 1:
        raise ValueError("one soil body expected")
    return name, m, bodies[0]


def load_points(function, name):
    """A case's time function as the points of a piecewise-linear history (docs/case-format.md,
    "Functions"): a number or constant (a step at 0), a ramp, a table."""
    if isinstance(function, (int, float)):
        return [(0.0, float(function))]
    kind = function.get("type")
    if kind == "constant":
        return [(0.0, float(function["value"]))]
    if kind == "ramp":
        return [(0.0, 0.0), (float(function["duration"]), float(function["value"]))]
    if kind == "table":
        points = [(float(t), float(v)) for t, v in function["points"]]
        if points[0][0] > 0.0:  # v0 before t0
            points.insert(0, (0.0, points[0][1]))
        return points
    raise ValueError(f"{name}: a {kind} function is not a history the closed forms superpose")


def integrate_points(points, t):
    """The integral from 0 to t of a piecewise-linear history (zero before its first point unless
    its first value is not, held after its last): a prescribed velocity's displacement."""
    times = np.array([q[0] for q in points], float)
    values = np.array([q[1] for q in points], float)
    if t <= times[0]:
        return values[0] * t if times[0] > 0 and values[0] != 0.0 else 0.0
    total = values[0] * times[0]
    k = int(np.searchsorted(times, t)) - 1
    total += np.sum(0.5 * (values[1:k + 1] + values[:k]) * np.diff(times[:k + 1]))
    if k + 1 < times.size:
        v_t = values[k] + (values[k + 1] - values[k]) * (t - times[k]) / (times[k + 1] - times[k])
    else:
        v_t = values[k]
    return total + 0.5 * (values[k] + v_t) * (t - times[k])


def toml_value(value):
    """A Python value (bool, number, str, list, dict) as TOML text; floats by repr, exact."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"no TOML for {value!r}")


def mpile_package():
    """The repository's Python package (python/mpile)."""
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "python"))
    import mpile
    return mpile


def expect_check(tool, items, names, check, results):
    """--expect NAME=BOUND items against a run's results: the bounds by name (each one of names),
    `check(results, bounds)` the failures. Prints "<tool> check: ok" or its failures and returns
    the exit status (1 on a failure); an unknown name exits with its message."""
    bounds = {}
    for item in items:
        name, _, bound = item.partition("=")
        if name not in names:
            sys.exit(f"--expect {item}: no such quantity")
        bounds[name] = float(bound)
    failures = check(results, bounds)
    print(f"{tool} check: " + ("ok" if not failures else "FAILED: " + "; ".join(failures)))
    return 1 if failures else 0
