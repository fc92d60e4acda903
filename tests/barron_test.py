#!/usr/bin/python3
"""tools/barron.py: Barron's free strain series against what it must satisfy.

  /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/barron_test.py

Python alone (numpy, scipy), under two seconds. The series is checked against an independent
solution of the same diffusion equation (a finite-volume grid, exact in time), against the
short-time expansion of the flux into a cylinder (Carslaw and Jaeger 1959, 13.5), against Barron's
equal strain solution where the two must agree, and at its ends (U(0) = 0, U -> 1); the load's
superposition against a numerical convolution; the lid case the tool writes against the series'
settlement; the grid's own scheme (GridFV) converging to the series at second order.
"""
import math
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tools"))
import barron  # noqa: E402
from case_numbers import assert_same_case  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
PLATE_CASE = ROOT / "cases/verification/radial_consolidation_plate.toml"
LID_CASE = ROOT / "cases/verification/radial_consolidation.toml"


@pytest.mark.parametrize("N", [2.0, 5.0, 10.0, 40.0])
def test_roots_solve_the_eigen_equation_one_per_interval(N):
    a = barron.eigenvalues(N, 400)
    # Z1(a N) = 0 to rounding: the residual within a few ulps of the function's scale there,
    # |Z1| <= |J1 Y0| + |Y1 J0| at the root, times the slope's N a eps.
    z1 = barron._z1(a * N, a)
    scale = (np.abs(barron.special.j1(a * N) * barron.special.y0(a))
             + np.abs(barron.special.y1(a * N) * barron.special.j0(a)))
    assert np.all(np.abs(z1) <= 64 * np.finfo(float).eps * scale * (1.0 + N * a))
    # Increasing, one per interval of the asymptotic spacing pi / (N - 1) (which they approach).
    gaps = np.diff(a)
    assert np.all(gaps > 0.999 * math.pi / (N - 1))
    assert abs(gaps[-1] / (math.pi / (N - 1)) - 1.0) < 1e-3
    # No root below the first: Z1 keeps its sign on (0, a_1) (the scan's step is a sixteenth of
    # the spacing; here on a grid 64 times finer).
    below = np.linspace(1e-6, a[0] * (1 - 1e-9), 4000)
    signs = np.sign(barron._z1(below * N, below))
    assert np.all(signs == signs[0])


@pytest.mark.parametrize("N", [5.0, 10.0, 20.0])
def test_series_against_the_finite_volume_solution(N):
    """The finite volume grid solves the same equation by other means (no Bessel functions): 400
    cells graded by 1.01 from the drain, its modes exact in time. Its error is second order in the
    cells (halving them quarters it: 1.3e-5 on 200 cells, 3.3e-6 on 400 for N = 10, measured), so
    the two must agree within 1e-5 at every time, the series' truncation being far smaller."""
    series = barron.FreeStrain(N)
    coarse, fine = barron.RadialFD(N, 200, 1.02), barron.RadialFD(N, 400, 1.01)
    times = np.geomspace(1e-3, 2.0, 40)
    err_fine = max(abs(fine.U(T) - series.U(T)) for T in times)
    err_coarse = max(abs(coarse.U(T) - series.U(T)) for T in times)
    assert err_fine < 1e-5
    assert 3.0 < err_coarse / err_fine < 5.0  # second order: the grid converges to the series
    # The pressure profile, not only its mean: within 1e-4 of u0 at every node at T_h = 0.01, 0.1.
    for T in (0.01, 0.1):
        rho = fine.r[::20]
        assert np.max(np.abs(series.pressure(rho, T) - fine.pressure(rho, T))) < 1e-4


def test_short_times_against_the_flux_into_a_cylinder():
    """U(0) = 0, and how it leaves 0: at short times only a thin layer around the well drains, as
    outside a cylinder in an infinite medium: with tau = c_h t / r_w^2, U = 2 (2 sqrt(tau / pi) +
    tau / 2 - tau^(3/2) / (6 sqrt(pi)) + tau^2 / 16 + ...) / (N^2 - 1) (the flux's expansion
    integrated, Carslaw and Jaeger 13.5). The next term is O(tau^(5/2)): at T_h = 1e-7 (tau = 4e-5)
    the two must agree to 1e-9 relative, at 1e-6 to 1e-7 (measured 8e-11, 8e-9). This also takes
    the series to thousands of terms (2 874 at T_h = 1e-7)."""
    N = 10.0
    series = barron.FreeStrain(N)
    assert series.U(0.0) == 0.0
    for T, bound in ((1e-7, 1e-9), (1e-6, 1e-7)):
        tau = 4.0 * N ** 2 * T
        drained = (2.0 * math.sqrt(tau / math.pi) + tau / 2.0
                   - tau ** 1.5 / (6.0 * math.sqrt(math.pi)) + tau ** 2 / 16.0)
        expansion = 2.0 * drained / (N ** 2 - 1.0)
        assert abs(series.U(T) / expansion - 1.0) < bound


def test_the_degree_of_consolidation_rises_to_one():
    series = barron.FreeStrain(10.0)
    times = np.geomspace(1e-6, 3.0, 80)
    U = np.array([series.U(T) for T in times])
    assert np.all(np.diff(U) > 0.0) and U[0] > 0.0
    # Late, only the slowest mode is left: 1 - U = w_1 exp(-4 a_1^2 N^2 T_h) (4.4e-7 at T_h = 3).
    w, _, _, rate = series.modes(50)
    assert 1.0 - series.U(3.0) == pytest.approx(w[0] * math.exp(-rate[0] * 3.0), rel=1e-6)
    assert 1.0 - series.U(3.0) < 1e-6
    # That mode's rate is close to equal strain's 8 / mu (the two solutions' long-time decay;
    # 4 % slower for N = 10, measured).
    assert 0.9 < rate[0] / (8.0 / barron.equal_strain_mu(10.0)) < 1.0
    # The mean weights sum to 1 (u = u0 at t = 0+): within what 20 000 terms leave (their tail
    # falls as 1 / k^2).
    w = series.modes(20000)[0]
    assert abs(w.sum() - 1.0) < 2e-5


@pytest.mark.parametrize("N", [5.0, 10.0, 20.0, 40.0])
def test_series_against_equal_strain(N):
    """Barron (1948) found free and equal strain close for N >= 5: equal strain lags early (its
    storage spread over the cell), then the two merge. Measured, the largest difference from T_h =
    0.05 on is 0.028 (N = 5), 0.025 (10), 0.018 (20), 0.012 (40), from T_h = 0.1 on 0.013 at most,
    and from T_h = 0.3 on 0.008 at most: the bounds below are those with a little room."""
    series = barron.FreeStrain(N)
    for start, bound in ((0.05, 0.03), (0.1, 0.014), (0.3, 0.009)):
        times = np.geomspace(start, 1.5, 30)
        assert max(abs(series.U(T) - barron.equal_strain_U(T, N)) for T in times) < bound
    # Equal strain lags at every time before they merge (its pore pressure is higher at the drain).
    assert all(barron.equal_strain_U(T, N) < series.U(T) for T in (0.005, 0.01, 0.02, 0.05))


def test_equal_strain_mu():
    # Hansbo (1981): mu = N^2 / (N^2 - 1) ln N - (3 N^2 - 1) / (4 N^2); for N = 10, 1.5783.
    mu = 100.0 / 99.0 * math.log(10.0) - 299.0 / 400.0
    assert barron.equal_strain_mu(10.0) == pytest.approx(mu)
    assert barron.equal_strain_mu(10.0) == pytest.approx(1.578344, abs=1e-6)
    T = -barron.equal_strain_mu(10.0) * math.log(0.1) / 8.0
    assert barron.equal_strain_U(T, 10.0) == pytest.approx(0.9)


def test_the_pressure_series_meets_its_boundary_conditions_and_its_mean():
    N = 10.0
    series = barron.FreeStrain(N)
    for T in (0.005, 0.05, 0.3):
        assert abs(series.pressure(1.0, T)[0]) < 1e-10  # drained at the well
        d = 1e-5
        slope = (series.pressure(N, T)[0] - series.pressure(N - d, T)[0]) / d
        assert abs(slope) < 1e-3 * series.pressure(N, T)[0] + 1e-8  # no flux at r_e
        rho = np.linspace(1.0, N, 4001)
        u = series.pressure(rho, T)
        mean = np.trapz(u * rho, rho) / (0.5 * (N ** 2 - 1.0))
        assert mean == pytest.approx(series.mean(T), abs=1e-6)


def test_surcharge_slab_coupling_leads_and_vanishes_at_half():
    """Under a free top (a surcharge) the skeleton moves radially: the thin slab's storage (1 +
    kappa) u - kappa <u> leads Barron's early and merges with it late; kappa = (1 - 2 nu) / (1 -
    nu) vanishes as nu -> 1/2."""
    assert barron.surcharge_slab(0.5) == 0.0
    assert barron.surcharge_slab(0.3) == pytest.approx(0.4 / 0.7)
    slab = barron.RadialFD(10.0, 300, 1.01, coupling=barron.surcharge_slab(0.3))
    series = barron.FreeStrain(10.0)
    lead = slab.U(0.038) - series.U(0.038)
    assert 0.005 < lead < 0.02  # measured 0.014 at U = 0.2 (T_h = 0.038)
    assert abs(slab.U(0.5) - series.U(0.5)) < 0.01


def test_superposition_over_a_ramp_against_a_numerical_convolution():
    """A load risen linearly over t_r: each mode's exponential integrated exactly over the rise,
    against the midpoint rule on the step response, u(t) = int_0^min(t, t_r) q' u_step(t - s) ds
    on 400 panels (its error O(panel^1.5) where the step response starts as 1 - c sqrt(t - s):
    under 1e-3 relative here)."""
    cell = barron.Cell(0.1, 1.0, 0.1, 7428571.428571429, 0.3, 0.39622641509433965, 2.2e9,
                       3.9297e-4, 1000.0, [(0.0, 0.0), (0.3, 1.0e4)])
    step = barron.FreeStrain(cell.N)
    for t in (0.1, 0.3, 0.5, 2.0):
        m = 400
        rise = min(t, 0.3)
        s = (np.arange(m) + 0.5) * rise / m
        response = np.array([step.mean(cell.T_h(t - x)) for x in s])
        convolution = np.sum(response) * (rise / m) * (1.0e4 / 0.3) * cell.B
        assert cell.mean(t) == pytest.approx(convolution, rel=1e-3)
    # After the rise, U(t) of a ramp lies between the step's at t and at t - t_r.
    t = 1.0
    assert step.U(cell.T_h(t - 0.3)) < cell.U(t) < step.U(cell.T_h(t))


def test_grid_scheme_converges_to_the_series_at_second_order():
    """GridFV (the engine's grid's own scheme) under a load converges to the series: its error at
    the times of U = 0.2, 0.5, 0.8 quarters as the cells halve (measured -0.0077, -0.0020,
    -0.0005 at U = 0.2 on 18, 36, 72 cells)."""
    case, text = barron.read_case(PLATE_CASE)
    cell, _ = barron.from_case(case, text)
    times = np.array([cell.time_at(U) for U in (0.2, 0.5, 0.8)])
    target = np.array([0.2, 0.5, 0.8])
    errors = [1.0 - barron.GridFV(cell, m).means(times) / cell.u0 - target for m in (18, 36)]
    assert np.all(np.abs(errors[0]) < 0.015)
    ratio = np.abs(errors[0]) / np.abs(errors[1])
    assert np.all((ratio > 3.0) & (ratio < 5.0))


def test_the_lid_case_moves_its_top_as_the_series_settles(tmp_path):
    """--write-lid: the shipped lid case is the one the tool writes from the plate case (its
    numbers to 1e-9 relative, 23 times the 4.3e-11 seen between machines: case_numbers.py), and
    its prescribed velocity integrates to the series' settlement at every interval's end."""
    out = tmp_path / "lid.toml"
    out.write_text(barron.lid_case_text(PLATE_CASE))
    assert_same_case(out.read_text(), LID_CASE.read_text(), relative=1e-9)
    case, text = barron.read_case(out)
    cell, info = barron.from_case(case, text)
    plate, _ = barron.from_case(*barron.read_case(PLATE_CASE))
    for key in ("r_w", "r_e", "H", "E_oed", "B", "c_h", "q"):
        assert getattr(cell, key) == pytest.approx(getattr(plate, key), rel=1e-12)
    velocity = info["lid_velocity"]
    for t in (0.01, 0.02, 0.1, 1.0, 5.0):
        ends = [p[0] + 1e-7 for p in velocity[1::2]]  # the intervals' ends
        te = min(ends, key=lambda e: abs(e - t))
        settled = -barron.integrate_points(velocity, te)
        assert settled == pytest.approx(cell.settlement(te), rel=1e-6, abs=1e-14)


def test_the_case_reads_as_documented():
    case, text = barron.read_case(PLATE_CASE)
    cell, info = barron.from_case(case, text)
    assert cell.N == pytest.approx(10.0)
    assert cell.E_oed == pytest.approx(1e7)
    assert cell.c_h == pytest.approx(0.4, rel=1e-5)
    assert cell.T_h(5.0) == pytest.approx(0.5, rel=1e-5)
    assert cell.B == pytest.approx(0.998202, abs=1e-6)
    assert info["plate"] == "plate"
    assert 0.37 < cell.time_at(0.2) < 0.39  # U = 0.2 at T_h = 0.038
