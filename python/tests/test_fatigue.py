"""Friction fatigue read from a history whose radial stress is known: a monitor oscillating about
a mean that falls by 1 kPa per cycle, dry, and a saturated one whose pore pressure rises."""
import numpy as np
import pytest
from conftest import write_history

import mpile
from mpile.files import RunFileError

FREQUENCY = 10.0  # Hz: a cycle is 0.1 s
ROWS_PER_CYCLE = 20


@pytest.fixture
def cycled(tmp_path):
    # Held for 0.2 s (two cycles' time), then cycled for 5 cycles; a row every 5 ms.
    time = np.arange(0, 0.7 + 1e-12, 0.1 / ROWS_PER_CYCLE)
    phase = (time > 0.2 + 1e-12).astype(np.int64)
    cycling = np.clip(time - 0.2, 0.0, None)
    # sigma'_r = 50 kPa - 1 kPa per cycle elapsed, plus a swing of +-5 kPa that each cycle's
    # mean removes (a sine over whole cycles averages to zero on the rows' midpoint rule).
    mean = 50e3 - 1e3 * FREQUENCY * cycling
    swing = 5e3 * np.sin(2 * np.pi * FREQUENCY * cycling)
    dry = -(mean + swing)                       # sigma_rr, tension positive
    pore = -10e3 - 2e3 * FREQUENCY * cycling    # pore pressure, tension positive: rising excess
    wet = dry + pore                            # total = effective + pore pressure
    return write_history(tmp_path / "history.h5", {
        "/time": (time, "s"),
        "/phase": (phase, "-"),
        "/monitors/dry/sigma_rr": (dry, "Pa"),
        "/monitors/wet/sigma_rr": (wet, "Pa"),
        "/monitors/wet/pore_pressure": (pore, "Pa"),
    }, attrs={"title": "cycled", "status": "complete"},
       phases=[{"name": "hold", "start": 0.0, "end": 0.2, "ended": "duration"},
               {"name": "cycling", "start": 0.2, "end": 0.7, "ended": "duration"}])


def test_cycle_means_against_the_known_decay(cycled):
    table = mpile.friction_fatigue(cycled, FREQUENCY)
    assert list(table.index) == [1, 2, 3, 4, 5]
    # Cycle N's rows lie at N - 1 + k / 20 cycles, k = 1..20: their mean elapsed is N - 0.475
    # cycles; the mean over the held cycle before is the start value 50 kPa (no swing yet).
    for n in range(1, 6):
        expected = (50e3 - 1e3 * (n - 0.475)) / 50e3
        # The sine's mean over 20 equally spaced rows of a whole cycle is zero to rounding.
        assert table.loc[n, "dry"] == pytest.approx(expected, rel=1e-9)
        # The pore pressure is taken out: the wet monitor's effective stress is the dry one's.
        assert table.loc[n, "wet"] == pytest.approx(expected, rel=1e-9)


def test_bad_requests_are_refused(cycled):
    with pytest.raises(ValueError):
        mpile.friction_fatigue(cycled, 0.0)
    with pytest.raises(RunFileError, match="no phase named 'shake'"):
        mpile.friction_fatigue(cycled, FREQUENCY, phase="shake")
    with pytest.raises(RunFileError, match="holds no whole cycle"):
        mpile.friction_fatigue(cycled, 1.0)
