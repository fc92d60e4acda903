#!/usr/bin/env python3
"""Reference integrator of sand hypoplasticity with intergranular strain, for element tests.

An independent, high-accuracy implementation in Python and numpy of

- von Wolffersdorff's hypoplastic model (1996, Mechanics of Cohesive-Frictional Materials 1:251-271),
- with Bauer's compression law for the limit void ratios (Bauer 1996, Soils and Foundations
  36(1):13-26) and Herle and Gudehus' f_b (1999, Mech. Cohes.-Frict. Mater. 4:461-486),
- and Niemunis and Herle's intergranular strain (1997, Mech. Cohes.-Frict. Mater. 2:279-299),

driven along laboratory paths (oedometer, isotropic, drained and undrained triaxial, undrained cyclic
triaxial with stress amplitudes, drained strain cycles, shear modulus decay). It is the reference
the engine's C++ implementation is tested against: the rate equations are integrated with an
adaptive embedded Runge-Kutta pair (Dormand-Prince 5(4)) to a relative tolerance of 1e-9, so a
curve from here is the model's exact response to about 1e-8.

    tools/hypoplastic_reference.py drained --params kfs --e0 0.80 --p0 100e3 --eps1 0.2 --out d.csv
    tools/hypoplastic_reference.py --help

Conventions
-----------
Inside the module, as in the engine (docs/physics.md section 1): stress and strain rate are
**tension positive**, full 3x3 symmetric tensors, the axes in the engine's order r, y, theta (index
0, 1, 2; six components rr, yy, thth, ry, ytheta, rtheta). The sample's axis is y: "axial" is
index 1, "lateral" are r and theta. p_s = -tr(sigma)/3 > 0 in compression. The void ratio rate is
e_dot = (1 + e) tr(D), so e = (1 + e0) exp(tr(eps)) - 1 with eps the integral of D (logarithmic
strain on these coaxial paths). Internally tensors are Mandel 6-vectors (normal components, then
sqrt(2) times the shears ry, ytheta, rtheta), in which A:B is a dot product and the symmetric
fourth-order identity is the 6x6 identity.

The path drivers take and report laboratory quantities in the soil-mechanics convention of the
engine's element-test CSV (docs/element-tests.md): **compression positive** eps_1 (axial), eps_v,
sigma_1 (axial), sigma_3 (radial), p = p_s, and q = sqrt(3 J2) signed as sigma_1 - sigma_3 (it is
sigma_1 - sigma_3 on triaxial paths). The full tension-positive tensors are returned as well.

The model (what is implemented, term by term)
----------------------------------------------
    s = sigma / tr(sigma) (hat T),  s_dev = s - I/3,  |X| = sqrt(X:X)
    a = sqrt(3) (3 - sin phi_c) / (2 sqrt(2) sin phi_c)
    F = sqrt(tan^2 psi / 8 + (2 - tan^2 psi) / (2 + sqrt(2) tan psi cos 3theta)) - tan psi / (2 sqrt 2)
        tan psi = sqrt(3) |s_dev|,  cos 3theta = -sqrt(6) tr(s_dev^3) / (s_dev:s_dev)^(3/2)
    e_i = e_i0 exp(-(3 p_s / h_s)^n), and e_c, e_d likewise with e_c0, e_d0      (Bauer)
    f_d = ((e - e_d) / (e_c - e_d))^alpha,  f_e = (e_c / e)^beta
    f_b = (h_s / n) ((1 + e_i) / e_i) (e_i0 / e_c0)^beta (3 p_s / h_s)^(1 - n)
          / (3 + a^2 - a sqrt(3) ((e_i0 - e_d0) / (e_c0 - e_d0))^alpha)
    L = f_b f_e / (s:s) (F^2 I4 + a^2 s (x) s),   N = f_d f_b f_e F a / (s:s) (s + s_dev)
    without intergranular strain:  sigma_dot = L:D + N |D|

The sign: with tension positive, tr(N) > 0, so an isochoric shear of an isotropic sample gives a
mean-stress rate tr(N)|D|/3 > 0, i.e. p_s falls (undrained contraction tendency); held at constant
p_s it must compress. At the critical state (sigma_dot = 0, tr D = 0, f_d = 1) the equations give
D/|D| = -(a/F) s_dev and |s_dev| = F/a: axial compression (D_yy < 0) goes with s_dev,yy > 0, which is
the triaxial-compression stress, and cos 3theta = -1 there. With this F the critical surface is
Matsuoka-Nakai's: q/p = M_c = 6 sin phi_c/(3 - sin phi_c) in compression and 6 sin phi_c/(3 + sin
phi_c) in extension (the tests check both).

Intergranular strain (Niemunis and Herle 1997), h symmetric, rho = |h|/R, h_hat = h/|h|:
    h_dot = (I4 - rho^beta_R h_hat (x) h_hat) : D   if h_hat:D > 0,   else h_dot = D
    M = [rho^chi m_T + (1 - rho^chi) m_R] L + rho^chi (1 - m_T) (L:h_hat) (x) h_hat + rho^chi N (x) h_hat
                                                                            if h_hat:D > 0
    M = [rho^chi m_T + (1 - rho^chi) m_R] L + rho^chi (m_R - m_T) (L:h_hat) (x) h_hat   otherwise
    sigma_dot = M : D
At rho = 1 and D parallel to h_hat this is L:D + N|D|; after a 180-degree reversal it is m_R L:D;
at h = 0 (rho = 0, h_hat taken as 0) it is m_R L:D and h_dot = D. Both branches agree on
h_hat:D = 0, so sigma_dot is continuous in D and in the state.

Choices where the papers leave room (documented because the C++ must make the same ones or differ
knowingly):
- F and cos 3theta at s_dev = 0: tan psi = 0 gives F = 1 for any cos 3theta; the code sets
  cos 3theta = -1 when |s_dev| < 1e-13 (it then multiplies zero). cos 3theta is clipped to [-1, 1]
  against rounding. A state with 2 + sqrt(2) tan psi cos 3theta <= 0 or a negative radicand is
  outside the model's domain (far beyond the critical surface) and raises OutOfDomain.
- p_s -> 0: s = sigma/tr(sigma) is undefined at tr(sigma) = 0 and f_b vanishes like p_s^(1 - n).
  There is no cut-off stress here: a state with p_s <= 0 raises OutOfDomain (the integrator retries
  a smaller step if a trial stage gets there; a path that really reaches it stops with the error).
  The undrained cyclic driver stops at p_s/p_s0 < 0.05 (liquefaction) long before. An engine
  cut-off (e.g. a minimum pressure) is outside this reference; compare above it.
- e outside [e_d, e_c]: f_d uses max(e - e_d, 0), so f_d = 0 (no N term, response L:D) at and
  below e_d; above e_c f_d > 1, and above e_i the formula is used as it is (no clipping).
- Triaxial paths keep sigma_r = sigma_theta by symmetry of the controls; nothing is imposed.

The path drivers (mixed control)
--------------------------------
Each path prescribes, per unit of a path parameter t, some Mandel components of D (strain
control) and the others of sigma_dot (stress control). At every stage of the Runge-Kutta step the
unknown strain rates are solved from sigma_dot_u(D) = target_u: without intergranular strain by
Newton on L_uu + N_u (x) D_u/|D| (sigma_dot is convex-homogeneous of degree 1 in D), with it by a
linear solve in the loading branch, accepted if h_hat:D > 0, else in the unloading branch. The
drivers return dicts of numpy arrays (see `path_result`); paths with stops (a target q, a
liquefaction criterion) locate them to about 1e-12 by re-stepping from the last accepted state.

Karlsruhe fine sand (KARLSRUHE_FINE_SAND)
-----------------------------------------
Wichtmann and Triantafyllidis (2016, Acta Geotechnica 11:739-761 and 763-774) published a
laboratory database of Karlsruhe fine sand (monotonic and cyclic triaxial, oedometric and isotropic
tests). The set below is, as recalled, the hypoplastic set with intergranular strain of Wichtmann,
Fuentes and Triantafyllidis (2019, Soil Dynamics and Earthquake Engineering 124:172-183, "Inspection
of three sophisticated constitutive models based on monotonic and cyclic tests on fine sand:
Hypoplasticity vs. Sanisand vs. ISA", its parameter table for hypoplasticity). Back-analyses of
vibratory driving in Karlsruhe sand (Chrisopoulos and Vogelsang 2019, Soil Dyn. Earthq. Eng.
122:248-260; Machacek, Staubach, Tafili, Zachert and Wichtmann 2021, Computers and Geotechnics 138,
as recalled) also use hypoplasticity with intergranular strain; whether their sets equal this one
was not checked.
Neither paper's table could be read from this machine. What was confirmed, number by number, from
two public input files that use this sand (a corroboration, not the primary source):
- [S] github.com/patrickstaubach/abaqus-implicit, step.inp (by P. Staubach; the material "soil" of
  a demonstration model, read in the order of its UMAT, HPP_Staubach_implicit.f): phi_c = 0.578 rad (33.1 degrees), h_s = 4e6 kPa, n = 0.27,
  e_d0 = 0.677, e_c0 = 1.054, e_i0 = 1.212, alpha = 0.14, beta = 2.5, m_T = 1.2, m_R = 2.4,
  R = 1e-4, beta_R = 0.1, chi = 6.
- [K] github.com/kokerozas/AdvanceHypoplasticModel2026, input_data_karlsuhe.m ("Final parameters
  karlsuhe sand", for a modified model): h_s = 4e6 kPa, n = 0.27, e_d0 = 0.677, e_c0 = 1.054,
  e_i0 = 1.212, m_R = 2.2, m_T = 1.1, R = 1e-4 (and its own phi_c = 32.5, beta_R = 0.15, chi = 5).
So the eight hypoplastic parameters and R, beta_R are those of [S] (h_s, n, e_d0, e_c0, e_i0 and R
also [K]'s);
e_d0 = 0.677 is also the value of the project's issue. m_R = 2.2 and m_T = 1.1 are [K]'s, where [S]
has 2.4 and 1.2; chi = 5.5 is NOT confirmed ([S] has 6, [K] 5): m_R, m_T and chi are the values
recalled for Wichtmann et al. (2019)'s table, by the engineer who asked for this file and by its
author independently. Check them against the paper before quoting them as its numbers; the
alternatives change only the intergranular-strain results.
The reference numbers in the tests and in any doc are of this dict as written.

There is no hypoplastic set for the seed paper's sand (it is a Hardening Soil sand, phi = 37.5
degrees, cases/monopile/base/seed_monopile.toml); `--params` takes `kfs` or a JSON file of the keys
of KARLSRUHE_FINE_SAND.
"""

import argparse
import csv
import json
import math
import sys

import numpy as np

# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------

# Karlsruhe fine sand; [S], [K] and what is confirmed: see the module docstring.
KARLSRUHE_FINE_SAND = {
    "phi_c": 33.1,    # degrees, critical friction angle   [S]
    "h_s": 4.0e9,     # Pa, granular hardness               [S], [K]
    "n": 0.27,        # exponent of Bauer's law             [S], [K]
    "e_d0": 0.677,    # densest void ratio at p = 0         [S], [K], the issue
    "e_c0": 1.054,    # critical void ratio at p = 0        [S], [K]
    "e_i0": 1.212,    # loosest void ratio at p = 0         [S], [K] (1.15 e_c0)
    "alpha": 0.14,    # peak-friction exponent of f_d       [S]
    "beta": 2.5,      # stiffness exponent of f_e           [S]
    "R": 1.0e-4,      # intergranular strain radius         [S], [K]
    "m_R": 2.2,       # stiffness factor, 180-degree turn   [K]; [S] has 2.4
    "m_T": 1.1,       # stiffness factor, 90-degree turn    [K]; [S] has 1.2
    "beta_R": 0.1,    # evolution exponent of h             [S]
    "chi": 5.5,       # interpolation exponent              NOT confirmed: [S] has 6, [K] 5
    "igs": True,      # with intergranular strain; False: sigma_dot = L:D + N|D|
}

PARAMETER_SETS = {"kfs": KARLSRUHE_FINE_SAND}

BASIC_KEYS = ("phi_c", "h_s", "n", "e_d0", "e_c0", "e_i0", "alpha", "beta")
IGS_KEYS = ("R", "m_R", "m_T", "beta_R", "chi")

RTOL = 1e-9  # default relative tolerance of the Runge-Kutta error control


def check_params(params):
    """Returns a checked copy (floats, igs defaulting to True); raises ValueError naming the key."""
    out = dict(params)
    out["igs"] = bool(out.get("igs", True))
    keys = BASIC_KEYS + (IGS_KEYS if out["igs"] else ())
    for key in keys:
        if key not in out:
            raise ValueError(f"missing parameter {key}")
        out[key] = float(out[key])
    if not 0.0 < out["phi_c"] < 90.0:
        raise ValueError("phi_c must be in (0, 90) degrees")
    for key in ("h_s", "n", "alpha", "beta"):
        if not out[key] > 0.0:
            raise ValueError(f"{key} must be positive")
    if not 0.0 < out["e_d0"] < out["e_c0"] < out["e_i0"]:
        raise ValueError("need 0 < e_d0 < e_c0 < e_i0")
    if out["igs"]:
        for key in IGS_KEYS:
            if not out[key] > 0.0:
                raise ValueError(f"{key} must be positive")
    unknown = set(out) - set(BASIC_KEYS) - set(IGS_KEYS) - {"igs"}
    if unknown:
        raise ValueError(f"unknown parameter(s): {', '.join(sorted(unknown))}")
    return out


def without_igs(params):
    """The same set with the intergranular strain switched off."""
    out = dict(params)
    out["igs"] = False
    return out


class OutOfDomain(ValueError):
    """A state where the model is undefined: p_s <= 0, e <= 0, or F undefined far beyond the
    critical surface."""


# --------------------------------------------------------------------------------------------------
# Tensors: 3x3 <-> Mandel 6-vectors (engine order r, y, theta; shears ry, ytheta, rtheta)
# --------------------------------------------------------------------------------------------------

SQRT2 = math.sqrt(2.0)
SQRT3 = math.sqrt(3.0)
SQRT6 = math.sqrt(6.0)
I6 = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])  # the second-order identity, Mandel
EYE6 = np.eye(6)  # the symmetric fourth-order identity I4, Mandel


def mandel(T):
    """Mandel vector of a symmetric 3x3 tensor: [T00, T11, T22, sqrt2 T01, sqrt2 T12, sqrt2 T02]."""
    T = np.asarray(T, dtype=float)
    return np.array([T[0, 0], T[1, 1], T[2, 2],
                     SQRT2 * T[0, 1], SQRT2 * T[1, 2], SQRT2 * T[0, 2]])


def tensor(m):
    """Symmetric 3x3 tensor of a Mandel vector."""
    a, b, c = m[3] / SQRT2, m[4] / SQRT2, m[5] / SQRT2
    return np.array([[m[0], a, c], [a, m[1], b], [c, b, m[2]]])


def engine6(T):
    """The engine's six components (rr, yy, thth, ry, ytheta, rtheta; tensor shears) of a 3x3."""
    T = np.asarray(T, dtype=float)
    return np.array([T[0, 0], T[1, 1], T[2, 2], T[0, 1], T[1, 2], T[0, 2]])


def from_engine6(v):
    """3x3 tensor from the engine's six components (tensor shears, not engineering)."""
    return np.array([[v[0], v[3], v[5]], [v[3], v[1], v[4]], [v[5], v[4], v[2]]], dtype=float)


class State:
    """sigma (3x3, Pa, tension positive), void ratio e, intergranular strain h (3x3)."""

    def __init__(self, sigma, e, h=None):
        self.sigma = np.array(sigma, dtype=float)
        self.e = float(e)
        self.h = np.zeros((3, 3)) if h is None else np.array(h, dtype=float)

    @classmethod
    def isotropic(cls, p, e, h=None):
        """An isotropic state at mean pressure p (Pa, compression positive) and void ratio e."""
        return cls(-float(p) * np.eye(3), e, h)

    @classmethod
    def triaxial(cls, sigma_axial, sigma_lateral, e, h=None):
        """sigma_yy = -sigma_axial, sigma_rr = sigma_thth = -sigma_lateral (inputs compression
        positive)."""
        lateral, axial = -float(sigma_lateral), -float(sigma_axial)
        return cls(np.diag([lateral, axial, lateral]), e, h)

    def copy(self):
        return State(self.sigma.copy(), self.e, self.h.copy())

    def __repr__(self):
        return (f"State(sigma={engine6(self.sigma).tolist()}, e={self.e!r}, "
                f"h={engine6(self.h).tolist()})")


# --------------------------------------------------------------------------------------------------
# The model
# --------------------------------------------------------------------------------------------------

def a_factor(phi_c_degrees):
    """a = sqrt(3) (3 - sin phi_c) / (2 sqrt(2) sin phi_c)."""
    s = math.sin(math.radians(phi_c_degrees))
    return SQRT3 * (3.0 - s) / (2.0 * SQRT2 * s)


def critical_stress_ratio(phi_c_degrees, extension=False):
    """q/p at the critical state: 6 sin phi_c / (3 -+ sin phi_c) (Matsuoka-Nakai in TC and TE)."""
    s = math.sin(math.radians(phi_c_degrees))
    return 6.0 * s / (3.0 + s) if extension else 6.0 * s / (3.0 - s)


def limit_void_ratios(params, p):
    """(e_i, e_c, e_d) at mean pressure p (Pa, compression positive): Bauer's law with 3 p / h_s."""
    x = math.exp(-((3.0 * p / params["h_s"]) ** params["n"]))
    return params["e_i0"] * x, params["e_c0"] * x, params["e_d0"] * x


def lode_factor(s_dev_m):
    """(F, cos 3theta) of the deviator s_dev of the normalised stress s (Mandel vector)."""
    norm = math.sqrt(float(s_dev_m @ s_dev_m))
    tan_psi = SQRT3 * norm
    if norm < 1e-13:
        cos3t = -1.0  # any value: it multiplies tan psi = 0, and F = 1
    else:
        S = tensor(s_dev_m)
        cos3t = -SQRT6 * float((S @ S @ S).trace()) / norm ** 3
        cos3t = min(1.0, max(-1.0, cos3t))
    denominator = 2.0 + SQRT2 * tan_psi * cos3t
    radicand = -1.0
    if denominator > 0.0:
        radicand = tan_psi ** 2 / 8.0 + (2.0 - tan_psi ** 2) / denominator
    if radicand < 0.0:
        raise OutOfDomain(f"F undefined: tan psi = {tan_psi:.6g}, cos 3theta = {cos3t:.6g}")
    return math.sqrt(radicand) - tan_psi / (2.0 * SQRT2), cos3t


def fb_denominator(params):
    """3 + a^2 - a sqrt(3) ((e_i0 - e_d0) / (e_c0 - e_d0))^alpha, the denominator of f_b."""
    a = a_factor(params["phi_c"])
    ratio = (params["e_i0"] - params["e_d0"]) / (params["e_c0"] - params["e_d0"])
    return 3.0 + a * a - a * SQRT3 * ratio ** params["alpha"]


def density_factors(params, e, p):
    """(f_b, f_e, f_d) at void ratio e and mean pressure p > 0 (Pa)."""
    if not e > 0.0:
        raise OutOfDomain(f"void ratio {e!r}")
    e_i, e_c, e_d = limit_void_ratios(params, p)
    beta, n, h_s = params["beta"], params["n"], params["h_s"]
    f_b = (h_s / n) * ((1.0 + e_i) / e_i) * (params["e_i0"] / params["e_c0"]) ** beta \
        * (3.0 * p / h_s) ** (1.0 - n) / fb_denominator(params)
    f_e = (e_c / e) ** beta
    f_d = (max(e - e_d, 0.0) / (e_c - e_d)) ** params["alpha"]
    return f_b, f_e, f_d


def hypoplastic_tensors(params, sigma_m, e):
    """(L, N): L as a 6x6 Mandel matrix, N as a Mandel vector, at stress sigma_m and void ratio e."""
    trace = sigma_m[0] + sigma_m[1] + sigma_m[2]
    if not trace < 0.0:
        raise OutOfDomain(f"p_s = {-trace / 3.0:.6g} Pa: the model needs compression (p_s > 0)")
    p = -trace / 3.0
    s = sigma_m / trace
    s_dev = s - I6 / 3.0
    F, _ = lode_factor(s_dev)
    a = a_factor(params["phi_c"])
    f_b, f_e, f_d = density_factors(params, e, p)
    c = f_b * f_e / float(s @ s)
    L = c * (F * F * EYE6 + a * a * (s[:, None] * s))
    N = (f_d * c * F * a) * (s + s_dev)
    return L, N


def _igs_matrices(params, L, N, h_m):
    """(M_loading, M_unloading, h_hat, rho) of the intergranular strain at h (Mandel)."""
    norm = math.sqrt(float(h_m @ h_m))
    if norm == 0.0:
        M = params["m_R"] * L
        return M, M, np.zeros(6), 0.0
    h_hat = h_m / norm
    rho = norm / params["R"]  # <= 1 exactly; the integrator's overshoot (~rtol) is pulled back
    rc = rho ** params["chi"]
    base = (rc * params["m_T"] + (1.0 - rc) * params["m_R"]) * L
    L_h = L @ h_hat
    loading = base + (rc * (1.0 - params["m_T"]) * L_h + rc * N)[:, None] * h_hat
    unloading = base + (rc * (params["m_R"] - params["m_T"]) * L_h)[:, None] * h_hat
    return loading, unloading, h_hat, rho


def _rates_m(params, sigma_m, e, h_m, D_m, LN=None, igs=None):
    """(sigma_dot, e_dot, h_dot) in Mandel form for a given strain rate D (Mandel); LN: (L, N) and
    igs: _igs_matrices at this state, if already computed."""
    L, N = hypoplastic_tensors(params, sigma_m, e) if LN is None else LN
    e_dot = (1.0 + e) * (D_m[0] + D_m[1] + D_m[2])
    if not params["igs"]:
        return L @ D_m + N * math.sqrt(float(D_m @ D_m)), e_dot, np.zeros(6)
    loading, unloading, h_hat, rho = _igs_matrices(params, L, N, h_m) if igs is None else igs
    hd = float(h_hat @ D_m)
    if hd > 0.0:
        return loading @ D_m, e_dot, D_m - (rho ** params["beta_R"] * hd) * h_hat
    return unloading @ D_m, e_dot, D_m.copy()


def stress_rate(params, state, D):
    """(sigma_dot, e_dot, h_dot) as 3x3 tensors (tension positive) for a strain rate D (3x3)."""
    params = check_params(params)
    sd, ed, hd = _rates_m(params, mandel(state.sigma), state.e, mandel(state.h), mandel(D))
    return tensor(sd), ed, tensor(hd)


def hypoplastic_stiffness(params, state):
    """(L, N) at a state as 3x3x3x3 and 3x3 arrays (tension positive): sigma_dot = L:D + N|D|."""
    params = check_params(params)
    L6, N6 = hypoplastic_tensors(params, mandel(state.sigma), state.e)
    L = np.zeros((3, 3, 3, 3))
    basis = []
    for k in range(6):
        unit = np.zeros(6)
        unit[k] = 1.0
        basis.append(tensor(unit))
    for k in range(6):
        for l in range(6):
            L += L6[k, l] * np.einsum("ij,kl->ijkl", basis[k], basis[l])
    return L, tensor(N6)


# --------------------------------------------------------------------------------------------------
# Mixed control: solving the unknown strain rates
# --------------------------------------------------------------------------------------------------

class Control:
    """Per unit path parameter t: Mandel components of D (strain control) where stress_mask is
    False, Mandel components of sigma_dot (stress control) where it is True."""

    def __init__(self, strain_rate, stress_rate=None, stress_mask=None):
        self.strain_rate = np.asarray(strain_rate, dtype=float)
        self.stress_rate = np.zeros(6) if stress_rate is None else np.asarray(stress_rate, float)
        self.stress_mask = np.zeros(6, bool) if stress_mask is None else np.asarray(stress_mask, bool)
        self.u = np.flatnonzero(self.stress_mask)  # unknown strain rates
        self.k = np.flatnonzero(~self.stress_mask)  # known ones
        self.uu, self.uk = np.ix_(self.u, self.u), np.ix_(self.u, self.k)  # their blocks
        self.guess = None  # last solution: the Newton start

    def solve(self, params, L, N, h_m, igs=None):
        """The full D (Mandel) meeting the controls at a state with hypoplastic tensors L, N and
        intergranular strain h_m (igs: its _igs_matrices, if already computed)."""
        D = np.where(self.stress_mask, 0.0, self.strain_rate)
        u, k, uu, uk = self.u, self.k, self.uu, self.uk
        if u.size == 0:
            return D
        target = self.stress_rate[u]
        if params["igs"]:
            loading, unloading, h_hat, _ = _igs_matrices(params, L, N, h_m) if igs is None else igs
            for M, is_loading in ((loading, True), (unloading, False)):
                D[u] = np.linalg.solve(M[uu], target - M[uk] @ D[k])
                if (float(h_hat @ D) > 0.0) == is_loading:
                    return D
            raise ArithmeticError("mixed control: neither intergranular-strain branch is consistent")
        # Without intergranular strain: Newton on L_uu D_u + N_u |D| = target - L_uk D_k.
        if self.guess is not None:
            D[u] = self.guess
        else:
            D[u] = np.linalg.solve(L[uu], target - L[uk] @ D[k])
        rhs = target - L[uk] @ D[k]
        Luu = L[uu]
        for _ in range(50):
            norm = math.sqrt(float(D @ D))
            residual = Luu @ D[u] + N[u] * norm - rhs
            J = Luu + N[u][:, None] * (D[u] / norm) if norm > 0.0 else Luu
            step = np.linalg.solve(J, residual)
            D[u] -= step
            # quadratic convergence: a step of 1e-13 of D leaves an error of order 1e-26
            if float(np.abs(step).max()) <= 1e-13 * (float(np.abs(D).max()) + 1e-300):
                self.guess = D[u].copy()
                return D
        raise ArithmeticError("mixed control: Newton did not converge")


# --------------------------------------------------------------------------------------------------
# Dormand-Prince 5(4) with error control, exact stops and located events
# --------------------------------------------------------------------------------------------------

# The Butcher tableau (the nodes c are not needed: the rates do not depend on t).
_A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
    (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84),
)
_B = _A[6] + (0.0,)  # fifth order; b7 = 0 (FSAL)
_E = (71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40)  # b5 - b4

# State vector y: sigma (6, Mandel), e, h (6, Mandel), eps (6, Mandel): 19 entries.
S_SIG, S_E, S_H, S_EPS = slice(0, 6), 6, slice(7, 13), slice(13, 19)


def _pack(state, eps=None):
    y = np.zeros(19)
    y[S_SIG] = mandel(state.sigma)
    y[S_E] = state.e
    y[S_H] = mandel(state.h)
    if eps is not None:
        y[S_EPS] = mandel(eps)
    return y


def _rhs(params, control, y):
    sigma_m, e, h_m = y[S_SIG], y[S_E], y[S_H]
    LN = hypoplastic_tensors(params, sigma_m, e)
    # The intergranular strain's matrices once a stage, for the mixed control and the rates.
    igs = _igs_matrices(params, *LN, h_m) if params["igs"] else None
    D = control.solve(params, *LN, h_m, igs)
    sd, ed, hd = _rates_m(params, sigma_m, e, h_m, D, LN, igs)
    out = np.empty(19)
    out[S_SIG] = sd
    out[S_E] = ed
    out[S_H] = hd if params["igs"] else 0.0
    out[S_EPS] = D
    return out


def _error_scale(params, y):
    """Per-component scale of the error norm: the stress by max(|sigma_i|, p_s), e by 1, h by R, eps
    by max(|eps_i|, 1e-3)."""
    scale = np.empty(19)
    p = max(-float(y[0] + y[1] + y[2]) / 3.0, 1e-300)
    scale[S_SIG] = np.maximum(np.abs(y[S_SIG]), p)
    scale[S_E] = 1.0
    scale[S_H] = params["R"] if params["igs"] else 1.0
    scale[S_EPS] = np.maximum(np.abs(y[S_EPS]), 1e-3)
    return scale


def _dp_step(params, control, y, k1, h):
    """One Dormand-Prince step of size h from y with first stage k1: (y_new, k7, error vector)."""
    ks = [k1]
    for i in range(1, 7):
        yi = y.copy()
        for j, aij in enumerate(_A[i]):
            if aij != 0.0:
                yi += (h * aij) * ks[j]
        ks.append(_rhs(params, control, yi))
    y_new = y.copy()
    err = np.zeros_like(y)
    for j in range(7):
        if _B[j] != 0.0:
            y_new += (h * _B[j]) * ks[j]
        if _E[j] != 0.0:
            err += (h * _E[j]) * ks[j]
    # Stage 7 sits at the fifth-order solution (its a-row is b), so ks[6] = f(y_new): FSAL.
    return y_new, ks[6], err


class Event:
    """Stop where g(y) crosses zero upwards (from < 0 to >= 0); name says which stop it was."""

    def __init__(self, name, g):
        self.name, self.g = name, g


def integrate(params, control, y0, t_end, stops=(), events=(), rtol=RTOL, record_steps=False,
              max_steps=2_000_000):
    """Integrates y' = f(y) for t in [0, t_end] with Dormand-Prince 5(4).

    Returns (ts, ys, event): the state at every stop in `stops` (0 < t <= t_end, steps land on
    them exactly) and at t_end, plus every accepted step if record_steps; event is the name of the
    Event that ended the integration early (then the last row is the located event) or None."""
    params = check_params(params)
    stops = sorted({float(t) for t in stops if 0.0 < t < t_end} | {float(t_end)})
    t, y = 0.0, np.array(y0, dtype=float)
    ts, ys = [0.0], [y.copy()]
    k1 = _rhs(params, control, y)
    h = t_end / 64.0
    g_prev = [ev.g(y) for ev in events]
    stop_index = 0
    h_free = h  # the step the error control asks for, before a stop shortens it
    for _ in range(max_steps):
        target = stops[stop_index]
        hits_stop = h_free >= target - t
        h = target - t if hits_stop else h_free
        try:
            y_new, k_new, err = _dp_step(params, control, y, k1, h)
            norm = float(np.abs(err / (rtol * _error_scale(params, y))).max())
            if not math.isfinite(norm):
                raise OutOfDomain("non-finite step")
        except (OutOfDomain, ArithmeticError, np.linalg.LinAlgError):
            if h < 1e-14 * t_end:
                raise
            h_free = 0.25 * h
            continue
        if norm > 1.0:
            h_free = h * max(0.1, 0.9 * norm ** -0.2)
            continue
        # accepted
        g_new = [ev.g(y_new) for ev in events]
        crossed = [i for i, (a, b) in enumerate(zip(g_prev, g_new)) if a < 0.0 <= b]
        if crossed:
            t_ev, y_ev, name = _locate_event(params, control, events, crossed, t, y, k1, h, g_prev)
            ts.append(t_ev)
            ys.append(y_ev)
            return np.array(ts), np.array(ys), name
        t = target if hits_stop else t + h
        y, k1, g_prev = y_new, k_new, g_new
        if hits_stop or record_steps:
            ts.append(t)
            ys.append(y.copy())
        if hits_stop:
            stop_index += 1
            if stop_index == len(stops):
                return np.array(ts), np.array(ys), None
        grown = h * min(5.0, 0.9 * max(norm, 1e-10) ** -0.2)
        h_free = max(grown, h_free) if hits_stop else grown
    raise ArithmeticError("integrate: too many steps")


def _locate_event(params, control, events, crossed, t, y, k1, h, g_prev):
    """The earliest crossing among `crossed` within (t, t + h]: Illinois false position on the step
    size, each trial a real Dormand-Prince step from (t, y). Returns (t_event, y_event, name)."""
    best = None
    for i in crossed:
        g = events[i].g
        lo, hi = 0.0, h
        g_lo = g_prev[i]
        y_hi = _dp_step(params, control, y, k1, hi)[0]
        g_hi = g(y_hi)
        side = 0
        for _ in range(200):
            if hi - lo <= 1e-14 * max(abs(t) + h, 1e-300) or g_hi == 0.0:
                break
            mid = hi - g_hi * (hi - lo) / (g_hi - g_lo)
            if not lo < mid < hi:
                mid = 0.5 * (lo + hi)
            y_mid = _dp_step(params, control, y, k1, mid)[0]
            g_mid = g(y_mid)
            if g_mid >= 0.0:
                hi, g_hi, y_hi = mid, g_mid, y_mid
                if side == -1:
                    g_lo *= 0.5
                side = -1
            else:
                lo, g_lo = mid, g_mid
                if side == 1:
                    g_hi *= 0.5
                side = 1
            if abs(g_mid) <= 1e-13 * (abs(g_prev[i]) + 1e-300) and g_mid >= 0.0:
                break
        if best is None or hi < best[0]:
            best = (hi, y_hi, events[i].name)
    return t + best[0], best[1], best[2]


# --------------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------------

def path_result(ts, ys, **extra):
    """Arrays of a path: t (the path parameter), sigma/eps/h (N x 3 x 3, tension positive), e, and
    the compression-positive laboratory columns eps_1 (axial), eps_r (radial), eps_v, sigma_1
    (axial), sigma_3 (radial), p, q (sqrt(3 J2) signed as sigma_1 - sigma_3), h_norm (|h|), and
    `state`, the final State."""
    ys = np.asarray(ys)
    sig = np.array([tensor(y[S_SIG]) for y in ys])
    eps = np.array([tensor(y[S_EPS]) for y in ys])
    h = np.array([tensor(y[S_H]) for y in ys])
    p = -np.trace(sig, axis1=1, axis2=2) / 3.0
    dev = sig + p[:, None, None] * np.eye(3)
    q_size = np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev))
    sign = np.where(-sig[:, 1, 1] + sig[:, 0, 0] >= 0.0, 1.0, -1.0)
    out = {
        "t": np.asarray(ts, dtype=float),
        "sigma": sig,
        "eps": eps,
        "h": h,
        "e": ys[:, S_E].copy(),
        "eps_1": 0.0 - eps[:, 1, 1],  # 0.0 - x: no -0.0 in the output
        "eps_r": 0.0 - eps[:, 0, 0],
        "eps_v": 0.0 - np.trace(eps, axis1=1, axis2=2),
        "sigma_1": 0.0 - sig[:, 1, 1],
        "sigma_3": 0.0 - sig[:, 0, 0],
        "p": p,
        "q": sign * q_size,
        "h_norm": np.sqrt(np.einsum("nij,nij->n", h, h)),
        "state": State(sig[-1], ys[-1, S_E], h[-1]),
    }
    out.update(extra)
    return out


def _concat(results, **extra):
    """One result from consecutive path results (the first row of each later one dropped)."""
    keys = [k for k, v in results[0].items() if isinstance(v, np.ndarray) and k != "t"]
    out = {k: np.concatenate([results[0][k]] + [r[k][1:] for r in results[1:]]) for k in keys}
    t, offset = [results[0]["t"]], results[0]["t"][-1]
    for r in results[1:]:
        t.append(r["t"][1:] + offset)
        offset += r["t"][-1]
    out["t"] = np.concatenate(t)
    out["state"] = results[-1]["state"]
    out.update(extra)
    return out


def run_path(params, state, control, t_end, steps=100, eps0=None, events=(), rtol=RTOL,
             record_steps=False):
    """The general mixed-control path: `control` (a Control) per unit t for t in [0, t_end], output
    at `steps` equal intervals (and every accepted step if record_steps), from `state` with the
    accumulated strain eps0 (3x3, default 0). Returns path_result(...) with `event`, the name of
    the Event that stopped it early, or None."""
    params = check_params(params)
    y0 = _pack(state, eps0)
    stops = [t_end * k / steps for k in range(1, steps + 1)] if steps else ()
    ts, ys, event = integrate(params, control, y0, t_end, stops, events, rtol, record_steps)
    return path_result(ts, ys, event=event)


def _mask(*stress_components):
    m = np.zeros(6, bool)
    m[list(stress_components)] = True
    return m


# --------------------------------------------------------------------------------------------------
# Path drivers (inputs compression positive, like the laboratory and the engine's element tests)
# --------------------------------------------------------------------------------------------------

def strain_path(params, state, D, t_end, steps=100, rtol=RTOL):
    """Fully strain-controlled: the constant strain rate D (3x3, tension positive, tensor shears)
    for t in [0, t_end]."""
    return run_path(params, state, Control(mandel(D)), t_end, steps, rtol=rtol)


def oedometer(params, state, eps_axial_total, steps=100, rtol=RTOL):
    """Oedometer, strain controlled: D_yy prescribed, lateral and shear strain rates zero.
    eps_axial_total > 0 compresses, < 0 unloads (compression-positive axial strain)."""
    sign = 1.0 if eps_axial_total >= 0.0 else -1.0
    control = Control([0.0, -sign, 0.0, 0.0, 0.0, 0.0])
    return run_path(params, state, control, abs(eps_axial_total), steps, rtol=rtol)


def oedometer_stress(params, state, sigma_axial_targets, steps=100, rtol=RTOL):
    """Oedometer, stress controlled as the engine's `oedometer` path: the axial stress moved
    linearly to each target in turn (Pa, compression positive), lateral and shear strains zero."""
    targets = np.atleast_1d(np.asarray(sigma_axial_targets, dtype=float))
    parts, eps = [], None
    for target in targets:
        current = -state.sigma[1, 1]
        sign = 1.0 if target >= current else -1.0
        control = Control(np.zeros(6), [0.0, -sign, 0.0, 0.0, 0.0, 0.0], _mask(1))
        r = run_path(params, state, control, abs(target - current), steps, eps, rtol=rtol)
        parts.append(r)
        state, eps = r["state"], r["eps"][-1]
    return _concat(parts)


def isotropic(params, state, p_target, steps=100, rtol=RTOL):
    """Isotropic compression (or unloading) to p_target (Pa): the three normal stresses change at
    the same rate, shear strains zero."""
    current = -np.trace(state.sigma) / 3.0
    sign = 1.0 if p_target >= current else -1.0
    control = Control(np.zeros(6), [-sign, -sign, -sign, 0.0, 0.0, 0.0], _mask(0, 1, 2))
    return run_path(params, state, control, abs(p_target - current), steps, rtol=rtol)


def drained_triaxial(params, state, eps1_max, steps=100, rtol=RTOL):
    """Drained triaxial: axial strain eps_1 prescribed up to eps1_max (> 0 compression, < 0
    extension), sigma_r = sigma_theta held (their rates zero), shear strains zero."""
    sign = 1.0 if eps1_max >= 0.0 else -1.0
    control = Control([0.0, -sign, 0.0, 0.0, 0.0, 0.0], np.zeros(6), _mask(0, 2))
    return run_path(params, state, control, abs(eps1_max), steps, rtol=rtol)


def _undrained_extras(r, p0):
    r["du"] = p0 - r["p"]                    # pore pressure change at constant total mean stress
    r["du_cell"] = p0 - r["p"] + r["q"] / 3.0  # at constant cell (total lateral) pressure
    return r


def undrained_triaxial(params, state, eps1_max, steps=100, rtol=RTOL):
    """Undrained (isochoric) triaxial: D = rate * diag(1/2, -1, 1/2), eps_1 up to eps1_max (> 0
    compression). p and q are effective; du = p0 - p is the excess pore pressure at constant total
    mean stress, du_cell = p0 - p + q/3 that at constant cell pressure."""
    sign = 1.0 if eps1_max >= 0.0 else -1.0
    control = Control([0.5 * sign, -sign, 0.5 * sign, 0.0, 0.0, 0.0])
    p0 = -np.trace(state.sigma) / 3.0
    return _undrained_extras(run_path(params, state, control, abs(eps1_max), steps, rtol=rtol), p0)


def _q_of(y):
    """q = sigma_1 - sigma_3 (compression positive, triaxial) of a state vector."""
    return -(y[1] - y[0])


def undrained_cyclic_triaxial(params, state, q_amplitude, n_cycles, p_ratio=0.05, eps_da=0.10,
                              rtol=RTOL, max_segment_strain=0.5):
    """Undrained cyclic triaxial with stress amplitudes: isochoric axial strain driven up until
    q = +q_amplitude, down until q = -q_amplitude, and so on (compression first), for n_cycles.

    Liquefaction, where it stops: p/p0 < p_ratio, or the double amplitude of eps_1 (the largest
    minus the smallest eps_1 so far) above eps_da. Returns the path (every accepted step) with
    n_liq, the number of cycles at liquefaction (quarter cycles counted as |q| moves: 0 -> A is one
    quarter, A -> -A two; fractional within the last segment by |q - q_start|/A; None if it did not
    liquefy), liquefied_by ('p_ratio', 'eps_da', 'max_segment_strain' if a segment ran
    max_segment_strain of axial strain without reaching its q, or None), and per completed cycle (q
    back at 0 from below) the arrays cycle_du (p0 - p), cycle_p and cycle_eps_1 (compression
    positive). du = p0 - p and du_cell = p0 - p + q/3 along the path, as in undrained_triaxial."""
    params = check_params(params)
    A = float(q_amplitude)
    p0 = -np.trace(state.sigma) / 3.0
    y = _pack(state)
    parts = []
    eps_min = eps_max = -y[S_EPS][1]
    quarters = 0.0
    cycle_du, cycle_p, cycle_eps = [], [], []
    # Segments: 0 -> +A, then per cycle: +A -> -A, -A -> 0 (cycle ends), 0 -> +A.
    targets = [A]
    for _ in range(n_cycles):
        targets += [-A, 0.0, A]
    targets = targets[:-1]  # the last cycle ends at q = 0
    q_start = _q_of(y)
    n_liq, how = None, None
    for target in targets:
        up = target > q_start
        sign = 1.0 if up else -1.0  # eps_1 increasing with q
        control = Control([0.5 * sign, -sign, 0.5 * sign, 0.0, 0.0, 0.0])
        lo, hi = eps_min, eps_max
        events = [
            Event("target", (lambda yy, tg=target: _q_of(yy) - tg) if up
                  else (lambda yy, tg=target: tg - _q_of(yy))),
            Event("p_ratio", lambda yy: p_ratio - (-(yy[0] + yy[1] + yy[2]) / 3.0) / p0),
            Event("eps_da", (lambda yy: (-yy[S_EPS][1] - lo) - eps_da) if up
                  else (lambda yy: (hi - (-yy[S_EPS][1])) - eps_da)),
        ]
        ts, ys, event = integrate(params, control, y, max_segment_strain, (), events, rtol,
                                  record_steps=True)
        parts.append(path_result(ts, ys))
        y = ys[-1]
        eps_now = -y[S_EPS][1]
        eps_min, eps_max = min(eps_min, eps_now), max(eps_max, eps_now)
        q_now = _q_of(y)
        if event != "target":
            quarters += abs(q_now - q_start) / A
            n_liq, how = quarters / 4.0, event if event else "max_segment_strain"
            break
        quarters += abs(target - q_start) / A
        if target == 0.0:
            p_now = -(y[0] + y[1] + y[2]) / 3.0
            cycle_du.append(p0 - p_now)
            cycle_p.append(p_now)
            cycle_eps.append(eps_now)
        q_start = target
    out = _concat(parts, n_liq=n_liq, liquefied_by=how, cycle_du=np.array(cycle_du),
                  cycle_p=np.array(cycle_p), cycle_eps_1=np.array(cycle_eps))
    return _undrained_extras(out, p0)


def drained_strain_cycles(params, state, eps_amplitude, n_cycles, steps=20, rtol=RTOL):
    """Drained axial strain cycles eps_1: 0 -> +A -> -A -> 0 per cycle (compression first), sigma_r
    and sigma_theta held. Returns the path (`steps` points per quarter) and cycle_eps_v, the
    volumetric strain (compression positive) at the end of each cycle (eps_1 back at 0)."""
    A = float(eps_amplitude)
    parts, eps = [], None
    cycle_eps_v = []
    for _ in range(n_cycles):
        for sign, length in ((1.0, A), (-1.0, 2.0 * A), (1.0, A)):
            control = Control([0.0, -sign, 0.0, 0.0, 0.0, 0.0], np.zeros(6), _mask(0, 2))
            n = steps * int(round(length / A))
            r = run_path(params, state, control, length, n, eps, rtol=rtol)
            parts.append(r)
            state, eps = r["state"], r["eps"][-1]
        cycle_eps_v.append(-np.trace(eps))
    return _concat(parts, cycle_eps_v=np.array(cycle_eps_v))


def shear_modulus_decay(params, state, gamma_amplitudes, steps=50, rtol=RTOL):
    """Secant shear modulus against engineering shear-strain amplitude, from the engine's
    cyclic-torsion path: gamma_ytheta prescribed, the three normal stresses held, the other shear
    strains zero. For each amplitude, from the same initial state: gamma 0 -> +g -> -g -> +g, and
    G_sec = (tau(+g) - tau(-g)) / (2 g) on the last (reloading) branch, tau = sigma_ytheta.

    Returns gamma (the amplitudes), G_sec, G0 and G_ratio = G_sec / G0. G0 is the initial tangent
    shear modulus with h = 0, m_R L_ytheta,ytheta,ytheta,ytheta (Mandel: m_R L[4, 4] / 2) at the
    initial state: m_R f_b f_e F^2 / (2 s:s) when sigma_ytheta = 0 (m_R taken as 1 without the
    intergranular strain)."""
    params = check_params(params)
    L, _ = hypoplastic_tensors(params, mandel(state.sigma), state.e)
    G0 = (params["m_R"] if params["igs"] else 1.0) * L[4, 4] / 2.0
    gammas = np.asarray(gamma_amplitudes, dtype=float)
    G_sec = []
    for g in gammas:
        s = state
        taus = []
        for sign, length in ((1.0, g), (-1.0, 2.0 * g), (1.0, 2.0 * g)):
            # Mandel D_4 = sqrt(2) D_ytheta = sqrt(2) gamma_dot / 2
            control = Control([0.0, 0.0, 0.0, 0.0, sign / SQRT2, 0.0], np.zeros(6), _mask(0, 1, 2))
            r = run_path(params, s, control, length, steps, rtol=rtol)
            s = r["state"]
            taus.append(s.sigma[1, 2])
        G_sec.append((taus[2] - taus[1]) / (2.0 * g))
    G_sec = np.array(G_sec)
    return {"gamma": gammas, "G_sec": G_sec, "G0": G0, "G_ratio": G_sec / G0}


# --------------------------------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------------------------------

PATHS = ("drained", "undrained", "oedometer", "oedometer-stress", "isotropic", "cyclic-undrained",
         "drained-cycles", "modulus-decay")

CSV_COLUMNS = ("eps_1", "eps_v", "sigma_1", "sigma_3", "p", "q", "e", "h_norm")


def _load_params(name, overrides):
    if name in PARAMETER_SETS:
        params = dict(PARAMETER_SETS[name])
    else:
        with open(name) as f:
            params = json.load(f)
    for item in overrides:
        key, _, value = item.partition("=")
        params[key] = value.lower() in ("1", "true", "yes") if key == "igs" else float(value)
    return check_params(params)


def _write_csv(path, result, extra_columns=()):
    columns = list(CSV_COLUMNS) + [c for c in extra_columns if c in result]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for i in range(len(result["t"])):
            writer.writerow([repr(float(result[c][i])) for c in columns])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="Outputs are compression positive (Pa, strains as fractions).")
    parser.add_argument("path", choices=PATHS)
    parser.add_argument("--params", default="kfs", help="kfs, or a JSON file of parameters")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="override a parameter (igs=false switches the intergranular strain off)")
    parser.add_argument("--e0", type=float, required=True, help="initial void ratio")
    parser.add_argument("--p0", type=float, required=True, help="initial isotropic pressure, Pa")
    parser.add_argument("--eps1", type=float, default=0.2,
                        help="drained, undrained, oedometer: final axial strain (compression > 0)")
    parser.add_argument("--targets", type=float, nargs="+", default=[400e3, 100e3],
                        help="oedometer-stress: axial stresses (Pa); isotropic: the first is p")
    parser.add_argument("--q-amp", type=float, default=30e3, help="cyclic-undrained: q amplitude, Pa")
    parser.add_argument("--cycles", type=int, default=50, help="cyclic paths: number of cycles")
    parser.add_argument("--eps-amp", type=float, default=1e-3, help="drained-cycles: eps_1 amplitude")
    parser.add_argument("--gammas", type=float, nargs="+", default=[1e-6, 1e-5, 1e-4, 1e-3, 1e-2],
                        help="modulus-decay: shear strain amplitudes")
    parser.add_argument("--steps", type=int, default=100, help="output points of a monotonic path")
    parser.add_argument("--rtol", type=float, default=RTOL, help="relative tolerance")
    parser.add_argument("--out", help="CSV of the path (not for modulus-decay, which prints its table)")
    args = parser.parse_args(argv)
    try:
        params = _load_params(args.params, args.set)
    except (OSError, ValueError) as error:
        print(f"hypoplastic_reference.py: {error}", file=sys.stderr)
        return 2
    state = State.isotropic(args.p0, args.e0)
    extra = ()
    if args.path == "drained":
        r = drained_triaxial(params, state, args.eps1, args.steps, args.rtol)
    elif args.path == "undrained":
        r = undrained_triaxial(params, state, args.eps1, args.steps, args.rtol)
        extra = ("du", "du_cell")
    elif args.path == "oedometer":
        r = oedometer(params, state, args.eps1, args.steps, args.rtol)
    elif args.path == "oedometer-stress":
        r = oedometer_stress(params, state, args.targets, args.steps, args.rtol)
    elif args.path == "isotropic":
        r = isotropic(params, state, args.targets[0], args.steps, args.rtol)
    elif args.path == "cyclic-undrained":
        r = undrained_cyclic_triaxial(params, state, args.q_amp, args.cycles, rtol=args.rtol)
        extra = ("du", "du_cell")
        print(f"cycles to liquefaction: {r['n_liq']!r} ({r['liquefied_by']})")
        for i, (du, p) in enumerate(zip(r["cycle_du"], r["cycle_p"]), 1):
            print(f"  cycle {i}: du = {du:.9g} Pa, p = {p:.9g} Pa")
    elif args.path == "drained-cycles":
        r = drained_strain_cycles(params, state, args.eps_amp, args.cycles, rtol=args.rtol)
        for i, ev in enumerate(r["cycle_eps_v"], 1):
            print(f"  cycle {i}: eps_v = {ev:.9g}")
    else:
        r = shear_modulus_decay(params, state, args.gammas, rtol=args.rtol)
        print(f"G0 = {r['G0']:.9g} Pa")
        print("gamma, G_sec (Pa), G_sec/G0")
        for g, G, ratio in zip(r["gamma"], r["G_sec"], r["G_ratio"]):
            print(f"{g:.6g}, {G:.9g}, {ratio:.9g}")
        return 0
    print(f"end: eps_1 = {r['eps_1'][-1]:.9g}, eps_v = {r['eps_v'][-1]:.9g}, p = {r['p'][-1]:.9g} Pa, "
          f"q = {r['q'][-1]:.9g} Pa, e = {r['e'][-1]:.9g}")
    if args.out:
        _write_csv(args.out, r, extra)
        print(f"wrote {len(r['t'])} rows to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
