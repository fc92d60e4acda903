#!/usr/bin/python3
"""tools/calibrate_seed_sand.py: the shipped hypoplastic set of the seed's sand is the one the case
files and docs/hypoplasticity.md carry; moving any fitted value by a little more than the resolution
it is quoted to does not lower the fit's objective; its scalars and the Hardening Soil targets are the numbers
docs/hypoplasticity.md quotes; the optimiser makes Nelder-Mead's moves.

    /usr/bin/python3 -m pytest tests/calibrate_seed_sand_test.py -q      (about 10 s on one core)

The objective is evaluated as the fit evaluates it (rtol 1e-6, 2e-4 of strain between triaxial
output points); the scalars the page quotes on the page's grid (1e-4) at rtol 1e-6.
"""

import pathlib
import re
import sys
import tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))

import calibrate_seed_sand as cs  # noqa: E402

CASES = ROOT / "cases" / "element_tests"
DOC = ROOT / "docs" / "hypoplasticity.md"

# case-file key -> key of the tool's set (mpile describe hypoplastic)
CASE_KEYS = {"critical_friction_angle": "phi_c", "granular_hardness": "h_s", "exponent": "n",
             "e_d0": "e_d0", "e_c0": "e_c0", "e_i0": "e_i0", "alpha": "alpha", "beta": "beta",
             "r_max": "R", "m_r": "m_R", "m_t": "m_T", "beta_r": "beta_R", "chi": "chi"}


# --------------------------------------------------------------------------------------------------
# (a) One set everywhere
# --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["seed_sand_hypoplastic_triaxial.toml",
                                  "seed_sand_hypoplastic_oedometer.toml"])
def test_the_case_files_carry_the_shipped_set(name):
    with open(CASES / name, "rb") as f:
        material = tomllib.load(f)["material"]
    assert material["type"] == "hypoplastic"
    from_file = {tool_key: float(material[key]) for key, tool_key in CASE_KEYS.items()}
    # exact: both are the same decimal literals
    assert from_file == cs.SHIPPED
    assert float(material["void_ratio"]) == cs.E0
    # the dry density the engine checks against e0: 2650 / (1 + e0), to the 0.01 kg/m^3 written
    assert material["density"] == pytest.approx(2650.0 / (1.0 + cs.E0), abs=0.005)


def doc_section():
    text = DOC.read_text()
    start = text.index("### The seed's sand")
    end = text.index("\n## ", start)
    return text[start:end]


def table_rows(section, header):
    """{first cell: [other cells]} of the markdown table whose header row starts with `header`."""
    lines = section.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(header))
    rows = {}
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows[cells[0]] = cells[1:]
    return rows


def test_the_page_quotes_the_shipped_set():
    rows = table_rows(doc_section(), "| phi_c | h_s |")
    assert len(rows) == 1
    first, rest = next(iter(rows.items()))
    values = [first] + rest
    header = ["phi_c", "h_s", "n", "e_d0", "e_c0", "e_i0", "alpha", "beta", "e0"]
    quoted = dict(zip(header, (float(v.split()[0]) for v in values)))
    assert quoted.pop("e0") == cs.E0
    quoted["h_s"] *= 1e6  # MPa on the page
    assert quoted == {k: cs.SHIPPED[k] for k in header[:-1]}


# --------------------------------------------------------------------------------------------------
# (b) A local optimum to its rounding
# --------------------------------------------------------------------------------------------------

# Each fitted value is moved by 1.2 times the resolution it is quoted to (cs.ROUNDING; phi_c, at
# its lower bound 30 deg, upwards only, by 1.2 times the 0.1 deg the case files write). If the
# objective's optimum along that parameter lay within half a unit of the shipped value, as
# rounding promises, a parabola through it rises both ways by at least (1.2^2 - 1.2) = 0.24 of its
# curvature over a unit: so a neighbour may come out lower only through the objective's numerical
# noise, which the tolerance covers. That noise: rtol 1e-6 against 1e-9 moves the objective of the
# shipped set by 6e-4 (3.7357 against 3.7351 on the same grid), and the fit itself stops when its
# simplex agrees to 1e-3 (1 + f), 0.005 here; TOLERANCE is twice that.
TOLERANCE = 0.01
STEPS = {"phi_c": 0.12, **{key: 1.2 * unit for key, unit in cs.ROUNDING.items()}}
MOVES = [("phi_c", +1)] + [(key, sign) for key in cs.ROUNDING for sign in (-1, +1)]

KNOWN = {}


@pytest.fixture(scope="module")
def targets():
    return cs.hs_targets()


@pytest.fixture(scope="module")
def shipped_objective(targets):
    return cs.objective(cs.SHIPPED, targets)


def test_the_shipped_set_is_inside_the_fits_bounds(shipped_objective):
    assert cs.admissible(cs.SHIPPED)
    assert shipped_objective < cs.OUT_OF_BOUNDS


@pytest.mark.parametrize("key,sign", [
    pytest.param(key, sign, marks=pytest.mark.xfail(strict=True, reason=KNOWN[(key, sign)]))
    if (key, sign) in KNOWN else (key, sign)
    for key, sign in MOVES], ids=[f"{k}{'+' if s > 0 else '-'}" for k, s in MOVES])
def test_moving_a_fitted_value_by_more_than_its_rounding_does_not_lower_the_objective(
        key, sign, targets, shipped_objective):
    delta = sign * STEPS[key]
    moved = cs.objective(cs.moved(cs.SHIPPED, key, delta), targets)
    assert moved < cs.OUT_OF_BOUNDS
    assert moved > shipped_objective - TOLERANCE, (
        f"{key} {delta:+.4g}: objective {moved:.4f} against the shipped {shipped_objective:.4f}")


def test_the_fits_best_set_rounds_to_the_shipped_one(targets):
    assert cs.rounded(cs.FITTED, targets) == cs.SHIPPED


# Nelder-Mead's moves, one iteration each (max_eval stops it after one), on functions given as
# tables of values so that the textbook rule (reflection 1, expansion 2, contraction 0.5, shrink
# 0.5) fixes every point it must ask for: (start, values by point, points asked in order).
MOVES_OF_NELDER_MEAD = {
    # the reflection 2 beats the best 1, so the expansion 1 + 2 (1 - 0) = 3 is tried and kept
    "expansion": ([0.0], {0: 0, 1: -1, 2: -2, 3: -3}, [0, 1, 2, 3]),
    # the reflection (1, -1) of the worst (0, 1) through (0.5, 0) lands between best and second
    "reflection": ([0.0, 0.0], {(0, 0): 0, (1, 0): 1, (0, 1): 2, (1, -1): 0.5},
                   [(0, 0), (1, 0), (0, 1), (1, -1)]),
    # the reflection 2 is no better than the best 1 but better than the worst 0: outside, 1.5
    "outside contraction": ([0.0], {0: 1, 1: 0, 2: 0.5, 1.5: 0.2}, [0, 1, 2, 1.5]),
    # the reflection 2 is worse than the worst 0: inside, halfway to it, 0.5
    "inside contraction": ([0.0], {0: 1, 1: 0, 2: 3, 0.5: 0.5}, [0, 1, 2, 0.5]),
    # reflection -1 and contraction 0.5 both worse than the worst 1: all but the best 0 halve to it
    "shrink": ([0.0], {0: 0, 1: 1, -1: 2, 0.5: 3}, [0, 1, -1, 0.5, 0.5]),
    # the start's values agree to 1e-3 (1 + f): nothing more is asked
    "stop": ([0.0], {0: 0, 1: 0.0005}, [0, 1]),
}


@pytest.mark.parametrize("move", MOVES_OF_NELDER_MEAD)
def test_nelder_mead_makes_the_textbook_move(move):
    x0, table, expected = MOVES_OF_NELDER_MEAD[move]
    asked = []

    def f(x):
        key = round(float(x[0]), 9) if len(x) == 1 else tuple(round(float(v), 9) for v in x)
        asked.append(key)
        return table[key]
    cs.nelder_mead(f, x0, [1.0] * len(x0), tol=1e-3, max_eval=4)
    assert asked == expected


def test_nelder_mead_finds_the_minimum_of_a_valley():
    # Rosenbrock's curved valley: minimum 0 at (1, 1); the fit's own settings but more evaluations
    def f(x):
        return 100.0 * (x[1] - x[0] ** 2) ** 2 + (1.0 - x[0]) ** 2
    x, value, evals = cs.nelder_mead(f, [-1.2, 1.0], [0.5, 0.5], tol=1e-12, max_eval=2000)
    assert value < 1e-8 and abs(x[0] - 1.0) < 1e-3 and abs(x[1] - 1.0) < 2e-3
    assert evals < 2000


# --------------------------------------------------------------------------------------------------
# (c) The numbers on the page
# --------------------------------------------------------------------------------------------------

NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?")


def quoted(cell):
    """[(value, half a unit of its last digit)] of the numbers in a table cell."""
    out = []
    for text in NUMBER.findall(cell):
        decimals = len(text.split(".")[1]) if "." in text else 0
        out.append((float(text), 0.5 * 10.0 ** -decimals))
    return out


@pytest.fixture(scope="module")
def model():
    # the page's triaxial grid (1e-4 of strain): E50 on the fit's 2e-4 grid is up to 0.13 % lower
    return cs.scalars(cs.SHIPPED, rtol=cs.FIT_RTOL, steps=cs.REPORT_STEPS, unloading=True)


@pytest.fixture(scope="module")
def page():
    return table_rows(doc_section(), "| quantity | Hardening Soil | hypoplastic |")


# The page's row -> (HS scalars, model scalars) in the page's units; None: a number the tool does not
# compute (HS's eps_v and secant are the engine's).
def rows_of(t, m):
    e50 = [f"E50_{int(s / 1e3)}" for s in cs.SIGMA3]
    phi = [f"phi_{int(s / 1e3)}" for s in cs.SIGMA3]
    return {
        "E50 at sigma_3 = 25 / 50 / 100 kPa (MPa)": ([t[k] for k in e50], [m[k] for k in e50]),
        "peak friction angle at 25 / 50 / 100 kPa": ([t[k] for k in phi], [m[k] for k in phi]),
        "eps_v at eps_1 = 10 %, 100 kPa": ([None], [100.0 * m["tx_100"]["eps_v_end"]]),
        "tangent Eoed at sigma_v = 100 kPa, from K0 = 0.5 at 10 kPa (MPa)":
            ([t["Eoed100"]], [m["Eoed100"]]),
        "eps_1 from 10 to 200 kPa, oedometer": ([100.0 * t["eps1_200"]], [100.0 * m["eps1_200"]]),
        "first unloading tangent from 200 kPa; secant to 50 kPa (MPa)":
            ([t["unload_tangent"], None], [m["unload_tangent"], m["unload_secant"]]),
    }


# The page rounds; its numbers are the model's at rtol 1e-9 and these are at 1e-6, which differ by
# at most 5.2e-5 relative on these scalars (measured: E50 at 100 kPa): a quoted number must lie
# within half a unit of its last digit, plus 1e-4 relative for the model's. The HS column is closed
# form on both sides: half a unit alone.
MODEL_SLACK = 1e-4


def test_the_page_quotes_every_row_the_test_knows(page, targets, model):
    assert set(page) == set(rows_of(targets, model))


@pytest.mark.parametrize("column", ["Hardening Soil", "hypoplastic"])
def test_the_pages_table_quotes_the_tools_numbers(column, page, targets, model):
    index = 0 if column == "Hardening Soil" else 1
    problems = []
    for label, sides in rows_of(targets, model).items():
        ours = sides[index]
        theirs = quoted(page[label][index])
        assert len(theirs) == len(ours), (label, page[label][index])
        for value, (number, half_unit) in zip(ours, theirs):
            if value is None:
                continue
            slack = half_unit + (MODEL_SLACK * abs(value) if index == 1 else 0.0)
            if not abs(value - number) <= slack:
                problems.append(f"{label}: the page has {number}, the tool {value:.6g}")
    assert not problems, "\n".join(problems)


def test_the_hs_targets_are_the_seeds_closed_forms(targets):
    # the HS reference of docs/hardening-soil.md: E50 = 44 MPa at 100 kPa, Eoed 31 766 / 44 000 kPa
    # at 50 / 100 kPa, m = 0.47, phi = 37.5 deg, K0nc = 0.5, Eur 132 MPa with nu_ur = 0.2
    assert targets["E50_100"] == pytest.approx(44.0, rel=1e-12)
    assert targets["E50_50"] == pytest.approx(31.766, abs=5e-4)
    assert targets["Eoed100"] == pytest.approx(44.0, rel=1e-12)
    assert all(targets[f"phi_{int(s / 1e3)}"] == 37.5 for s in cs.SIGMA3)
    assert targets["k0_nc"] == 0.5
    assert targets["unload_tangent"] == pytest.approx(132.0 * 0.8 / (1.2 * 0.6), rel=1e-12)
