#!/usr/bin/env python3
"""tools/hypoplastic_reference.py against closed forms: the critical state (Matsuoka-Nakai stress
ratios, e -> e_c), the e_i line of isotropic compression, rate independence, the intergranular
strain's stiffnesses (m_R L at h = 0 and after a reversal, L:D + N|D| when fully mobilised),
dilatancy of dense and contraction of loose sand, undrained cyclic liquefaction, the small-cycle
ratcheting the intergranular strain removes, and the integrator's own convergence.

    /usr/bin/python3 -m pytest tests/hypoplastic_reference_test.py -q      (under 10 s)

Each tolerance says why it is what it is; each test can fail (one of them shows it does, by
breaking the model on purpose).
"""

import math
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tools"))

import hypoplastic_reference as hr  # noqa: E402

KFS = hr.KARLSRUHE_FINE_SAND
HYPO = hr.without_igs(KFS)
PHI = KFS["phi_c"]
M_C = hr.critical_stress_ratio(PHI)
M_E = hr.critical_stress_ratio(PHI, extension=True)


def e_c(p):
    return hr.limit_void_ratios(KFS, p)[1]


def e_i(p):
    return hr.limit_void_ratios(KFS, p)[0]


def rel(a, b):
    return abs(a - b) / abs(b)


# --------------------------------------------------------------------------------------------------
# The stress functions
# --------------------------------------------------------------------------------------------------

def test_mandel_round_trip_and_engine_order():
    T = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 5.0], [3.0, 5.0, 6.0]])
    assert np.abs(hr.tensor(hr.mandel(T)) - T).max() <= 1e-15 * np.abs(T).max()
    # engine order rr, yy, thth, ry, ytheta, rtheta with r, y, theta = 0, 1, 2
    assert hr.engine6(T).tolist() == [1.0, 4.0, 6.0, 2.0, 5.0, 3.0]
    assert np.array_equal(hr.from_engine6(hr.engine6(T)), T)
    # A:B is the Mandel dot product
    B = np.arange(9.0).reshape(3, 3)
    B = B + B.T
    assert math.isclose(hr.mandel(T) @ hr.mandel(B), float(np.sum(T * B)), rel_tol=1e-15)


def test_F_is_one_at_isotropic_stress_and_matsuoka_nakai_at_the_critical_state():
    # s_dev = 0: tan psi = 0, F = 1 whatever cos 3theta is.
    F, _ = hr.lode_factor(np.zeros(6))
    assert F == 1.0
    # Critical state: |s_dev| = F/a (sigma_dot = 0 with tr D = 0, f_d = 1). With this F it holds
    # at q/p = 6 sin phi/(3 - sin phi) in compression and 6 sin phi/(3 + sin phi) in extension, the
    # Matsuoka-Nakai ratios; 1e-12 is rounding in a closed form.
    a = hr.a_factor(PHI)
    for ratio, axial_sign, cos3t_expected in ((M_C, 1.0, -1.0), (M_E, -1.0, 1.0)):
        p = 1.0
        q = ratio * p
        # axial compression positive stresses: sigma_a = p + 2q/3 (TC) or p - 2q/3 (TE)
        sig = hr.State.triaxial(p + axial_sign * 2 * q / 3, p - axial_sign * q / 3, 1.0).sigma
        s = hr.mandel(sig) / np.trace(sig)
        s_dev = s - hr.I6 / 3
        F, cos3t = hr.lode_factor(s_dev)
        assert math.isclose(cos3t, cos3t_expected, abs_tol=1e-12)
        assert math.isclose(math.sqrt(s_dev @ s_dev), F / a, rel_tol=1e-12)


def test_critical_state_is_stationary_under_isochoric_shear_in_its_direction():
    # At q/p = M_c and e = e_c(p), D = -(a/F) s_dev |D| gives sigma_dot = 0 and e_dot = 0 exactly
    # (both terms of L:D + N|D| are computed separately, so 1e-12 of their size is rounding).
    p = 150e3
    state = hr.State.triaxial(p + 2 * M_C * p / 3, p - M_C * p / 3, e_c(p))
    s = state.sigma / np.trace(state.sigma)
    D = -(s - np.eye(3) / 3)
    D /= np.linalg.norm(D)
    rate, e_dot, _ = hr.stress_rate(HYPO, state, D)
    L, N = hr.hypoplastic_stiffness(HYPO, state)
    size = np.linalg.norm(np.einsum("ijkl,kl->ij", L, D))
    assert np.abs(rate).max() < 1e-12 * size
    assert abs(e_dot) < 1e-15


def test_loose_sand_contracts_the_N_term_lowers_p_under_isochoric_shear():
    # Sign convention check: tension positive, sigma_dot = L:D + N|D|. Isochoric shear of an
    # isotropic sample: L:D has no trace, N|D| has a positive one, so p_s falls (undrained
    # contraction); with f_d = 0 (e = e_d) the fall vanishes.
    p = 100e3
    D = np.diag([0.5, -1.0, 0.5])
    for e, falls in ((e_c(p), True), (hr.limit_void_ratios(KFS, p)[2], False)):
        rate, _, _ = hr.stress_rate(HYPO, hr.State.isotropic(p, e), D)
        p_dot = -np.trace(rate) / 3
        assert (p_dot < -1e-6 * p) if falls else (abs(p_dot) < 1e-9 * p)


def test_stress_free_state_is_out_of_the_domain():
    with pytest.raises(hr.OutOfDomain):
        hr.stress_rate(HYPO, hr.State.isotropic(0.0, 0.8), np.eye(3))
    with pytest.raises(hr.OutOfDomain):
        hr.stress_rate(HYPO, hr.State.isotropic(-1.0, 0.8), np.eye(3))


# --------------------------------------------------------------------------------------------------
# Critical state along paths
# --------------------------------------------------------------------------------------------------

def test_drained_triaxial_reaches_the_critical_state():
    # The approach is exponential in the (logarithmic) axial strain with an e-folding length of
    # about 0.45: 40 % leaves 5 % (dense) of the gap, so the path runs to eps_1 = 3, where the gap
    # is below 1e-3 from both sides. 1e-3: the tolerance asked for, with margin 2.5 (dense) to 20.
    for e0 in (0.80, 1.00):
        r = hr.drained_triaxial(HYPO, hr.State.isotropic(100e3, e0), 3.0, steps=6)
        assert rel(r["q"][-1] / r["p"][-1], M_C) < 1e-3
        assert rel(r["e"][-1], e_c(r["p"][-1])) < 1e-3
        # and it is an approach: the gap at 3.0 is a fraction of that at 1.0
        assert rel(r["e"][-1], e_c(r["p"][-1])) < 0.2 * rel(r["e"][2], e_c(r["p"][2]))
        # the lateral stress is held (stress control to rounding)
        assert np.abs(r["sigma_3"] - 100e3).max() < 1e-6


def test_undrained_triaxial_reaches_the_critical_state():
    # e stays e0 (isochoric, to rounding); p moves to where e_c(p) = e0, q/p to M_c. At eps_1 = 2
    # the gaps are below 3e-4; 1e-3 as asked.
    for e0 in (0.95, 1.00):
        r = hr.undrained_triaxial(HYPO, hr.State.isotropic(100e3, e0), 2.0, steps=4)
        assert np.abs(r["e"] - e0).max() < 1e-12
        assert rel(r["q"][-1] / r["p"][-1], M_C) < 1e-3
        assert rel(e0, e_c(r["p"][-1])) < 1e-3
        # the closed-form end pressure p_c(e0) = h_s/3 ln(e_c0/e0)^(1/n)
        p_cs = KFS["h_s"] / 3 * math.log(KFS["e_c0"] / e0) ** (1 / KFS["n"])
        assert rel(r["p"][-1], p_cs) < 1e-2  # 1e-3 in e is about n/(e gap) = 4e-3 in p; margin


def test_dense_dilates_with_a_peak_and_loose_contracts_without_one():
    dense = hr.drained_triaxial(HYPO, hr.State.isotropic(100e3, 0.70), 0.3, steps=300)
    loose = hr.drained_triaxial(HYPO, hr.State.isotropic(100e3, 1.05), 0.3, steps=300)
    eta_d = dense["q"] / dense["p"]
    eta_l = loose["q"] / loose["p"]
    # dense: a peak stress ratio well above M_c (1.39 M_c at eps_1 = 3 %), then softening towards
    # M_c (1.10 M_c at 30 %; the rest of the way is in test_drained_triaxial_reaches_the_critical_
    # state); it ends dilating (eps_v falling) and looser than it started
    assert eta_d.max() > 1.2 * M_C
    assert M_C < eta_d[-1] < 0.85 * eta_d.max()
    assert dense["eps_v"][-1] < dense["eps_v"][-2] and dense["e"][-1] > 0.70
    # loose: contracts all the way, and q/p rises monotonically towards M_c from below (0.976 M_c
    # at 30 %), never above
    assert np.all(np.diff(loose["eps_v"]) > 0.0) and loose["e"][-1] < 1.05
    assert np.all(np.diff(eta_l[1:]) > 0.0) and 0.95 * M_C < eta_l[-1] < M_C


# --------------------------------------------------------------------------------------------------
# Isotropic compression: the e_i line
# --------------------------------------------------------------------------------------------------

def _isotropic_gap(params, e0, p_end):
    r = hr.isotropic(params, hr.State.isotropic(100e3, e0), p_end, steps=10)
    return np.array([e / e_i(p) - 1.0 for e, p in zip(r["e"], r["p"])])


def test_isotropic_compression_on_the_e_i_line_stays_on_it():
    # f_b is built so that e = e_i(p) is an invariant of isotropic compression: the gap stays at
    # the integrator's tolerance (1e-9 per step; 1e-8 allows for the 10 stops and rounding).
    gap = _isotropic_gap(HYPO, e_i(100e3), 100e6)
    assert np.abs(gap).max() < 1e-8


def test_the_e_i_check_fails_if_the_f_b_denominator_is_altered(monkeypatch):
    # The same check with 3 + a^2 instead of 3 + a^2 - a sqrt(3) (...)^alpha: off by 18 %.
    a = hr.a_factor(PHI)
    monkeypatch.setattr(hr, "fb_denominator", lambda params: 3.0 + a * a)
    gap = _isotropic_gap(HYPO, e_i(100e3), 100e6)
    assert np.abs(gap).max() > 1e-2


def test_isotropic_compression_tends_to_e_i_from_both_sides():
    # Below e_i the sample is stiffer than on the line, above it softer, so the gap closes
    # monotonically from both sides (slowly: over 100 kPa to 1 GPa it shrinks by a factor > 4).
    for e0 in (0.95, 1.15):
        gap = np.abs(_isotropic_gap(HYPO, e0, 1e9))
        assert np.all(np.diff(gap) < 0.0)
        assert gap[-1] < 0.25 * gap[0]


# --------------------------------------------------------------------------------------------------
# Rate independence, symmetry
# --------------------------------------------------------------------------------------------------

def test_stress_rate_is_homogeneous_of_degree_one_in_D():
    state = hr.State(np.diag([-80e3, -150e3, -90e3]) + 5e3 * (np.ones((3, 3)) - np.eye(3)), 0.85,
                     h=4e-5 * np.diag([1.0, -1.0, 0.2]))
    rng = np.random.default_rng(1)
    for params in (HYPO, KFS):
        for _ in range(5):
            D = rng.normal(size=(3, 3))
            D = D + D.T
            r1, e1, h1 = hr.stress_rate(params, state, D)
            r2, e2, h2 = hr.stress_rate(params, state, 1000.0 * D)
            assert np.abs(r2 - 1000.0 * r1).max() <= 1e-13 * np.abs(r2).max()
            assert abs(e2 - 1000.0 * e1) <= 1e-13 * abs(e2)
            assert np.abs(h2 - 1000.0 * h1).max() <= 1e-13 * np.abs(h2).max()


def test_paths_are_rate_independent_and_keep_their_symmetry():
    # The same path driven 1000 times faster over a 1000 times shorter parameter ends in the same
    # state: 1e-8 relative is ten times the integrator's tolerance.
    state = hr.State.isotropic(100e3, 0.80)
    lateral_stress_held = [1, 0, 1, 0, 0, 0]
    for params in (HYPO, KFS):
        slow = hr.run_path(params, state, hr.Control([0, -1, 0, 0, 0, 0], np.zeros(6), lateral_stress_held),
                           0.05, steps=1)
        fast = hr.run_path(params, state, hr.Control([0, -1000, 0, 0, 0, 0], np.zeros(6), lateral_stress_held),
                           0.05e-3, steps=1)
        for key in ("sigma", "eps", "h"):
            scale = np.abs(slow[key][-1]).max()
            assert np.abs(fast[key][-1] - slow[key][-1]).max() <= 1e-8 * scale
        assert abs(fast["e"][-1] - slow["e"][-1]) < 1e-8
        # a pure element test: no shear stress or strain appears, sigma_r = sigma_theta
        for r in (slow, fast):
            off = r["sigma"][-1] - np.diag(np.diag(r["sigma"][-1]))
            assert np.abs(off).max() == 0.0
            assert abs(r["sigma"][-1][0, 0] - r["sigma"][-1][2, 2]) < 1e-9 * r["p"][-1]


# --------------------------------------------------------------------------------------------------
# Intergranular strain
# --------------------------------------------------------------------------------------------------

def _tangent_from_two_tiny_steps(params, state, D, delta):
    """(4 dsigma(delta) - dsigma(2 delta)) / (2 delta): the initial tangent, second order in delta."""
    d1 = hr.strain_path(params, state, D, delta, steps=1)["sigma"][-1] - state.sigma
    d2 = hr.strain_path(params, state, D, 2 * delta, steps=1)["sigma"][-1] - state.sigma
    return (4 * d1 - d2) / (2 * delta)


def _hypoplastic_response(state, D):
    L, N = hr.hypoplastic_stiffness(HYPO, state)
    return np.einsum("ijkl,kl->ij", L, D), N * np.linalg.norm(D)


def test_intergranular_strain_at_h_zero_gives_m_R_L():
    # Any direction, h = 0: rho = 0, M = m_R L. delta = 1e-8 (R/1e4): the tangent's change over it
    # is below 1e-9; 1e-7 allows for rounding of the tiny increments (1e-11 Pa in 0.5 Pa).
    state = hr.State(np.diag([-90e3, -120e3, -90e3]), 0.80)
    D = np.array([[0.3, 0.2, 0.0], [0.2, -1.0, 0.1], [0.0, 0.1, 0.4]])
    D /= np.linalg.norm(D)
    T = _tangent_from_two_tiny_steps(KFS, state, D, 1e-8)
    LD, _ = _hypoplastic_response(state, D)
    assert np.abs(T - KFS["m_R"] * LD).max() < 1e-7 * np.abs(LD).max()


def test_intergranular_strain_after_a_full_reversal_and_when_fully_mobilised():
    # rho = 1: h = R h_hat. D = -h_hat (a 180-degree reversal) gives m_R L:D; D = +h_hat gives the
    # hypoplastic L:D + N|D|. delta = 1e-9: chi delta / R = 5.5e-5 is the step's second-order
    # term, cancelled by the extrapolation; 1e-7 relative is the third-order rest and rounding.
    state = hr.State(np.diag([-90e3, -120e3, -90e3]), 0.80)
    D = np.diag([0.5, -1.0, 0.5]) / math.sqrt(1.5)
    LD, ND = _hypoplastic_response(state, D)
    reversed_state = hr.State(state.sigma, state.e, h=-KFS["R"] * D)
    T = _tangent_from_two_tiny_steps(KFS, reversed_state, D, 1e-9)
    assert np.abs(T - KFS["m_R"] * LD).max() < 1e-7 * np.abs(LD).max()
    mobilised = hr.State(state.sigma, state.e, h=KFS["R"] * D)
    T = _tangent_from_two_tiny_steps(KFS, mobilised, D, 1e-9)
    assert np.abs(T - (LD + ND)).max() < 1e-7 * np.abs(LD).max()
    # and the check has teeth: m_R L differs from L:D + N|D| by far more than the tolerance
    assert np.abs(KFS["m_R"] * LD - (LD + ND)).max() > 0.1 * np.abs(LD).max()


def test_monotonic_loading_converges_to_the_hypoplastic_response():
    # Isochoric triaxial (a fixed D direction) from h = 0: 1 - rho decays like exp(-beta_R |D| eps
    # / R), below 1e-10 after 2 %, so the intergranular strain's rate equals L:D + N|D| to 1e-8.
    state = hr.State.isotropic(100e3, 0.90)
    r = hr.undrained_triaxial(KFS, state, 0.02, steps=1)
    end = r["state"]
    assert rel(np.linalg.norm(end.h), KFS["R"]) < 1e-9
    D = np.diag([0.5, -1.0, 0.5])
    with_igs, _, _ = hr.stress_rate(KFS, end, D)
    without, _, _ = hr.stress_rate(HYPO, end, D)
    assert np.abs(with_igs - without).max() < 1e-8 * np.abs(without).max()
    # the two curves themselves converge (towards the same critical state): the gap in p, 13 % at
    # eps_1 = 10 %, is under 1e-3 at 300 % (2e-4 measured)
    a = hr.undrained_triaxial(KFS, state, 3.0, steps=30)
    b = hr.undrained_triaxial(HYPO, state, 3.0, steps=30)
    gap = np.abs(a["p"] / b["p"] - 1.0)
    assert gap[-1] < 1e-3 and gap[-1] < 0.01 * gap[1]


def test_small_drained_cycles_ratchet_far_less_with_intergranular_strain():
    # Axial strain cycles of 1e-4 (= R) at sigma_3 = 100 kPa: hypoplasticity alone accumulates
    # about 3e-4 of volumetric strain per cycle; with the intergranular strain the response is
    # nearly elastic and accumulates under 1 % of that.
    state = hr.State.isotropic(100e3, 0.80)
    hypo = hr.drained_strain_cycles(HYPO, state, 1e-4, 3, steps=5)["cycle_eps_v"]
    igs = hr.drained_strain_cycles(KFS, state, 1e-4, 3, steps=5)["cycle_eps_v"]
    assert np.all(np.diff(hypo) > 1e-4) and hypo[-1] > 5e-4  # contraction every cycle
    assert abs(igs[-1]) < 0.01 * hypo[-1]


def test_shear_modulus_decays_from_G0():
    # Below R the secant modulus is the initial m_R L stiffness (within 1e-3 at gamma = R/100); it
    # decays monotonically and is below 30 % at gamma = 1 %.
    r = hr.shear_modulus_decay(KFS, hr.State.isotropic(100e3, 0.80), [1e-6, 1e-5, 1e-4, 1e-3, 1e-2],
                               steps=10)
    ratio = r["G_ratio"]
    assert ratio[0] > 0.999 and ratio[0] <= 1.0 + 1e-9
    assert np.all(np.diff(ratio) < 0.0)
    assert ratio[-1] < 0.3
    # G0 is m_R f_b f_e F^2 / (2 s:s) at an isotropic state (F = 1, s:s = 1/3)
    f_b, f_e, _ = hr.density_factors(KFS, 0.80, 100e3)
    assert rel(r["G0"], KFS["m_R"] * f_b * f_e * 1.5) < 1e-12


# --------------------------------------------------------------------------------------------------
# Undrained cyclic triaxial
# --------------------------------------------------------------------------------------------------

def test_undrained_cyclic_loading_of_loose_sand_liquefies():
    # q = +-30 kPa at p0 = 100 kPa, e0 = 0.95 (loose: D_r = 28 % between e_d0 and e_c0): p falls
    # every cycle and the sample liquefies within a finite number of cycles, hypoplasticity alone
    # within a few, and later with the intergranular strain (which makes the small-strain response
    # nearly elastic).
    state = hr.State.isotropic(100e3, 0.95)
    hypo = hr.undrained_cyclic_triaxial(HYPO, state, 30e3, 20)
    igs = hr.undrained_cyclic_triaxial(KFS, state, 30e3, 40)
    for r in (hypo, igs):
        assert r["n_liq"] is not None and r["liquefied_by"] in ("p_ratio", "eps_da")
        assert np.all(np.diff(r["cycle_du"]) > 0.0)
        assert np.abs(r["e"] - 0.95).max() < 1e-12  # isochoric
        # at the stop: p/p0 = 0.05 or a double amplitude of 10 %, located to 1e-9
        if r["liquefied_by"] == "p_ratio":
            assert abs(r["p"][-1] / 100e3 - 0.05) < 1e-9
        else:
            assert abs(r["eps_1"].max() - r["eps_1"].min() - 0.10) < 1e-9
    assert hypo["n_liq"] < 5
    assert igs["n_liq"] > hypo["n_liq"]
    # the stress amplitude is met exactly at each reversal (the stops are located to ~1e-12 of it)
    q = igs["q"]
    turning = [i for i in range(1, len(q) - 1) if (q[i] - q[i - 1]) * (q[i + 1] - q[i]) < 0]
    assert turning and all(abs(abs(q[i]) - 30e3) < 1e-6 for i in turning)


# --------------------------------------------------------------------------------------------------
# The integrator
# --------------------------------------------------------------------------------------------------

def test_halving_the_tolerance_changes_the_result_by_less_than_1e_8():
    state = hr.State.isotropic(100e3, 0.80)
    for params in (HYPO, KFS):
        a = hr.drained_triaxial(params, state, 0.05, steps=5, rtol=1e-9)
        b = hr.drained_triaxial(params, state, 0.05, steps=5, rtol=5e-10)
        for key in ("q", "p", "e", "eps_v"):
            scale = np.abs(b[key]).max()
            assert np.abs(a[key] - b[key]).max() < 1e-8 * scale


def test_oedometer_stress_path_meets_its_targets_and_unloads_stiffer():
    # 100 -> 400 kPa brings the isotropic sample to its K0 state; 400 -> 1600 -> 400 kPa is then a
    # K0 loading and unloading, where unloading recovers a fraction of the void ratio (about 0.3).
    state = hr.State.isotropic(100e3, 0.80)
    for params in (HYPO, KFS):
        r = hr.oedometer_stress(params, state, [400e3, 1600e3, 400e3], steps=10)
        assert np.abs(r["sigma_1"][[10, 20, 30]] - [400e3, 1600e3, 400e3]).max() < 1e-6
        assert np.abs(r["eps_r"]).max() < 1e-15  # no lateral strain
        loading = r["e"][10] - r["e"][20]
        unloading = r["e"][30] - r["e"][20]
        assert loading > 0 and 0 < unloading < 0.5 * loading
        # K0 = sigma_3/sigma_1 on loading is below 1 and rises on unloading
        assert r["sigma_3"][20] / 1600e3 < 0.5 < r["sigma_3"][30] / 400e3


def test_command_line_writes_the_csv(tmp_path):
    out = tmp_path / "d.csv"
    assert hr.main(["drained", "--e0", "0.8", "--p0", "100e3", "--eps1", "0.01", "--steps", "4",
                    "--out", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert lines[0] == "eps_1,eps_v,sigma_1,sigma_3,p,q,e,h_norm"
    assert len(lines) == 6 and float(lines[-1].split(",")[0]) == pytest.approx(0.01, rel=1e-12)
    assert hr.main(["drained", "--params", str(tmp_path / "missing.json"), "--e0", "0.8",
                    "--p0", "1e5"]) == 2
