#!/usr/bin/python3
"""tools/step_levels.py: the multi-rate step's particle updates on counts known by hand, and Hardening
Soil's constrained modulus at p_ref and at the floor.

  /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/step_levels_test.py
"""
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tools"))
import step_levels  # noqa: E402


def test_levels_and_the_multirate_cost_of_known_counts():
    # Crossing times 1, 1.5, 2, 3.9, 4 and 9 units: levels 0, 0, 1, 1, 2, 3. One step for all
    # updates 6 particles per smallest step; with two levels 2 + 4 / 2 = 4, with all four
    # 2 + 2 / 2 + 1 / 4 + 1 / 8 = 3.375 (exact in binary, so compared exactly).
    level = step_levels.levels(np.array([1.0, 1.5, 2.0, 3.9, 4.0, 9.0]))
    assert level.tolist() == [0, 0, 1, 1, 2, 3]
    assert step_levels.multirate_cost(level, 0) == 1.0
    assert step_levels.multirate_cost(level, 1) == 4.0 / 6.0
    assert step_levels.multirate_cost(level, 3) == 3.375 / 6.0


def test_the_constrained_modulus_follows_the_unloading_stiffness():
    sand = {"friction_angle": 30.0, "p_ref": 100e3, "eur_ref": 120e6, "power": 0.5, "poisson_ur": 0.2}
    # nu = 0.2: M = E (0.8) / (1.2 * 0.6) = 10 E / 9. At sigma_3 = p_ref, E = E_ur,ref; at a
    # quarter of it, half; in tension the stress ratio is floored at 0.01: E = 0.1 E_ur,ref.
    modulus = step_levels.unloading_constrained_modulus(sand, np.array([100e3, 25e3, -5e3]))
    assert modulus == pytest.approx(np.array([120e6, 60e6, 12e6]) * 10.0 / 9.0, rel=1e-14)
