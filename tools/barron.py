#!/usr/bin/python3
"""Radial consolidation towards a drain well (Barron 1948): the references, and a run against them.

  tools/barron.py --case cases/verification/radial_consolidation.toml   # U(T_h) at a few times
  tools/barron.py --compare out/radial_consolidation                    # a run against the series
  tools/barron.py --write-lid cases/verification/radial_consolidation_plate.toml \\
      cases/verification/radial_consolidation.toml        # the lid case from the plate case

The unit cell: a cylinder of soil r_w <= r <= r_e around a drain well of radius r_w (N = r_e /
r_w), drained at r = r_w (u = 0 there), impermeable at r = r_e, top and bottom, under a vertical
load applied at t = 0+ and held; the water flows radially only. u is the excess pore pressure
(compression positive here), u0 = B q the undrained one, and with Darcy's k, the water's unit
weight gamma_w and the soil's storage per unit pore pressure S = 1 / E_oed + n / K_w

  du/dt = c_h (d2u/dr2 + (1/r) du/dr),   c_h = k / (gamma_w S),
  T_h = c_h t / d_e^2 = c_h t / (4 r_e^2)

(Barron's and Hansbo's convention: T_h over the equivalent diameter d_e = 2 r_e squared).

Free strain (Barron 1948, his "free vertical strain"): the equation above with u(r_w) = 0 and
du/dr(r_e) = 0. Separation of variables with Z0(x) = J0(x) Y0(a) - Y0(x) J0(a), which vanishes at
r = r_w (x = a r / r_w), gives the eigen-equation (the flux through r_e is zero):

  Z1(a N) = J1(a N) Y0(a) - Y1(a N) J0(a) = 0,           a_1 < a_2 < ...

and, with rho = r / r_w, Z1(a) = J1(a) Y0(a) - Y1(a) J0(a) = 2 / (pi a) (the Wronskian), the
integrals int_1^N Z0(a rho) rho drho = -2 / (pi a^2) and int_1^N Z0^2 rho drho = N^2 Z0(a N)^2 / 2
- 2 / (pi a)^2:

  u(r, t) / u0 = sum_k c_k Z0(a_k r / r_w) exp(-4 a_k^2 N^2 T_h),   c_k = (-2 / (pi a_k^2)) /
                 (N^2 Z0(a_k N)^2 / 2 - 2 / (pi a_k)^2)
  U(T_h)       = 1 - mean of u / u0 over the annulus (weight r)
               = 1 - sum_k 16 exp(-4 a_k^2 N^2 T_h) / (pi^2 a_k^4 (N^2 - 1) (N^2 Z0(a_k N)^2
                 - 4 / (pi a_k)^2))

which is Barron's series (his U1(a) = Z1(a), U0(a N) = Z0(a N)). The roots are bracketed by a scan
at a sixteenth of their asymptotic spacing pi / (N - 1) (the spacing falls towards it from above)
and bisected to adjacent doubles. Equal strain (Barron 1948; Hansbo 1981): U = 1 - exp(-8 T_h /
mu), mu = N^2 / (N^2 - 1) ln N - (3 N^2 - 1) / (4 N^2) (no smear, no well resistance); for N >= 5
it is within a few hundredths of the free strain series from T_h = 0.05 on and the two merge as T_h
grows. A finite-volume (finite-difference) solution of the diffusion equation on a graded radial
grid, exact in time (its modes from the symmetric eigenproblem), checks the series independently
(tests/barron_test.py).

Which loading the free strain series solves exactly, in the engine's poroelasticity (Biot, grains
incompressible: docs/physics.md 9b). A cell between a base on rollers and a rigid, frictionless,
impermeable top (a plate pressed by a force, or a lid moved down), rollers at r_w and r_e: the
top settles uniformly, u_y = eps(t) y, and u_r(r, t) does not vary with y, so no shear arises and
the problem is exactly one-dimensional in r. Radial equilibrium, d/dr (sigma_rr) + (sigma_rr -
sigma_thth) / r = 0, integrates to (lambda + 2 G) e - u = C(t) with e = eps_rr + eps_thth; u_r = 0
at both rollers makes the area mean of e zero, so e = (u - <u>) / E_oed, and the plate's force
balance E_oed eps - <u> = -q gives eps = (<u> - q) / E_oed. The volumetric strain is then
(u - q) / E_oed at every r, Barron's free strain storage, and the storage equation of the water,
d(eps_vol)/dt + (n / K_w) du/dt = (k / gamma_w) lap u, is the diffusion equation above: **under a
rigid top the free strain series is the exact solution**, u0 = B q with B = (K_w / n) / (E_oed +
K_w / n), and Barron's equal strain solution (which takes eps_vol = eps, no radial motion) is the
approximation. Under a surcharge (a free top) the vertical strain varies with r and the skeleton
moves radially with it: eps_vol = (u - <u>) / (lambda + G) + (<u> - q) / E_oed in a thin slab, not
Barron's problem (`surcharge_slab` below; it leads the series by 0.014 at U = 0.2 at nu = 0.3).
The engine has no free face that holds the water either (every free face drains: physics.md 9b).

The engine's case (cases/verification/radial_consolidation.toml) moves the top line down with the
series' settlement, s(t) = H (q(t) - <u>(t)) / E_oed, by a [[prescribed]] velocity (a held DOF
holds the water too: the top is impermeable), so that the pore pressures must be the series'.
cases/verification/radial_consolidation_plate.toml presses a rigid plate with the force q A, A =
(r_e^2 - r_w^2) / 2 per radian, instead (there the engine ties the water to the skeleton at the
plate's nodes, physics.md 9b). The load rises over a time short against the consolidation (the
run's inertia); --compare superposes the series over the load's own piecewise-linear history,
exactly (each mode's exponential integrated over each segment), and so does --write-lid for the
lid's motion.

From the engine's parameters: E_oed = E (1 - nu) / ((1 + nu) (1 - 2 nu)), n = 1 - rho_d / rho_s,
k measured under standard gravity (gamma_w = rho_w 9.80665: engine/materials/pore_water.hpp), so
c_h = k / (rho_w g0 (1 / E_oed + n / K_w)), V10's c_v (docs/verification.md).

--compare reads the run's snapshots (particles.pvd: U = 1 - the soil's volume-weighted mean excess
pore pressure / u0, the volume per radian weighting by r) and, under the plate, its settlement (U =
1 - (q - E_oed s / H) / u0), and prints U against the free strain series, equal strain and the
grid's own finite-volume scheme (GridFV: the engine's cells and nodes without particles), the
differences where the series has U = 0.2, 0.5 and 0.8, the lid's reaction (which lacks the water
the lid holds: below), then by cell the pore pressure against the series' cell mean and the water's
flux through each node over the Darcy flux of its neighbouring cells' pressures (from the cells'
water balance: where the run departs first), and the monitors.
"""
import argparse
import math
import pathlib
import sys

import numpy as np
from scipy import linalg, special

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from case_history import (coupled_soil, expect_check, integrate_points, load_points,  # noqa: E402
                          mpile_package, toml_value)

STANDARD_GRAVITY = 9.80665  # engine/materials/pore_water.hpp: k is measured under it
LOAD_TAG = "# barron.py load (t s, q Pa):"  # the lid case's load history, for --compare
U_LEVELS = (0.2, 0.5, 0.8)


# --- the free strain series -------------------------------------------------------------------

def _z0(x, a):
    return special.j0(x) * special.y0(a) - special.y0(x) * special.j0(a)


def _z1(x, a):
    return special.j1(x) * special.y0(a) - special.y1(x) * special.j0(a)


def eigenvalues(N, count):
    """The first `count` positive roots a of J1(a N) Y0(a) - Y1(a N) J0(a) = 0 (a = beta r_w)."""
    if not N > 1.0:
        raise ValueError(f"N = r_e / r_w must exceed 1, got {N}")
    spacing = math.pi / (N - 1.0)
    step = spacing / 16.0
    found = np.empty(0)
    start = 0.5 * step
    chunk = 16 * (count + 8)
    while found.size < count:
        a = start + step * np.arange(chunk + 1)
        f = _z1(a * N, a)
        change = np.nonzero(np.sign(f[:-1]) != np.sign(f[1:]))[0]
        lo, hi = a[change], a[change + 1]
        flo = np.sign(_z1(lo * N, lo))
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            same = np.sign(_z1(mid * N, mid)) == flo
            lo = np.where(same, mid, lo)
            hi = np.where(same, hi, mid)
            if np.all(np.nextafter(lo, hi) >= hi):
                break
        found = np.concatenate([found, 0.5 * (lo + hi)])
        start = a[-1]
    roots = found[:count]
    # Check: one root per asymptotic interval (spacing falling towards pi / (N - 1) from above).
    gaps = np.diff(roots)
    if gaps.size and not (np.all(gaps > 0.999 * spacing) and np.all(gaps < 2.0 * spacing)):
        raise ArithmeticError("the roots' spacing is not the expected one: a root was missed")
    return roots


class FreeStrain:
    """Barron's free strain series for a cell of ratio N: the step response to a load at t = 0+.
    Times as T_h = c_h t / (4 r_e^2); pressures as u / u0."""

    def __init__(self, N):
        self.N = float(N)
        self._roots = np.empty(0)

    def roots(self, count):
        if self._roots.size < count:
            self._roots = eigenvalues(self.N, max(count, 2 * self._roots.size))
        return self._roots[:count]

    def terms_for(self, T_h):
        """Terms enough that the first left out has exp(-4 a^2 N^2 T_h) < e^-40 (the roots grow
        as k pi / (N - 1))."""
        if T_h <= 0.0:
            return 20000
        k = (self.N - 1.0) / math.pi * math.sqrt(40.0 / (4.0 * self.N ** 2 * T_h))
        return int(min(20000, max(50, k + 10)))

    def modes(self, count):
        """(mean weights, pressure coefficients, roots, rates per unit T_h)."""
        a = self.roots(count)
        N = self.N
        z0N = _z0(a * N, a)
        norm = 0.5 * N ** 2 * z0N ** 2 - 2.0 / (math.pi * a) ** 2  # int Z0^2 rho drho
        integral = -2.0 / (math.pi * a ** 2)  # int Z0 rho drho
        coefficient = integral / norm
        mean_weight = integral * coefficient / (0.5 * (N ** 2 - 1.0))
        return mean_weight, coefficient, a, 4.0 * a ** 2 * N ** 2

    def mean(self, T_h):
        """The annulus' mean u / u0 at T_h (1 at T_h = 0)."""
        if T_h <= 0.0:
            return 1.0
        w, _, _, rate = self.modes(self.terms_for(T_h))
        return float(np.sum(w * np.exp(-rate * T_h)))

    def U(self, T_h):
        return 1.0 - self.mean(T_h)

    def pressure(self, rho, T_h):
        """u / u0 at r / r_w = rho (array), T_h > 0."""
        _, c, a, rate = self.modes(self.terms_for(T_h))
        rho = np.atleast_1d(np.asarray(rho, float))
        return np.array([np.sum(c * _z0(a * x, a) * np.exp(-rate * T_h)) for x in rho])


def equal_strain_mu(N):
    N2 = float(N) ** 2
    return N2 / (N2 - 1.0) * math.log(N) - (3.0 * N2 - 1.0) / (4.0 * N2)


def equal_strain_U(T_h, N):
    """Barron's equal strain (Hansbo 1981, no smear, no well resistance): 1 - exp(-8 T_h / mu)."""
    return 1.0 - math.exp(-8.0 * T_h / equal_strain_mu(N))


# --- a finite-volume solution of the radial diffusion equation -------------------------------

class RadialFD:
    """The diffusion equation on nodes r_w = r_0 < ... < r_M = r_e (in units of r_w), cells
    growing geometrically by `growth` from the drain; a vertex-centred finite volume (flux r du/dr
    at the faces midway between nodes, each node's storage its annulus), u = 0 at the drain node,
    no flux at r_e. Exact in time: C du/dt = -K u in tau = c_h t / r_w^2 = 4 N^2 T_h is solved by
    its modes (the symmetric eigenproblem K phi = lambda C phi). With `coupling` kappa > 0 the
    storage is (1 + kappa) u - kappa <u> per unit volume instead of u (the same for a uniform u):
    the thin slab under a surcharge (surcharge_slab)."""

    def __init__(self, N, cells=400, growth=1.01, coupling=0.0):
        self.N = float(N)
        sizes = growth ** np.arange(cells)
        r = np.concatenate([[1.0], 1.0 + np.cumsum(sizes) * (self.N - 1.0) / sizes.sum()])
        r[-1] = self.N
        self.r = r
        faces = 0.5 * (r[1:] + r[:-1])
        edges = np.concatenate([[r[0]], faces, [r[-1]]])
        area = 0.5 * (edges[1:] ** 2 - edges[:-1] ** 2)
        self.area = area
        conductance = faces / np.diff(r)
        M = cells
        K = np.zeros((M + 1, M + 1))
        idx = np.arange(M)
        K[idx, idx] += conductance
        K[idx + 1, idx + 1] += conductance
        K[idx, idx + 1] -= conductance
        K[idx + 1, idx] -= conductance
        total = area.sum()
        C = (1.0 + coupling) * np.diag(area) - coupling * np.outer(area, area) / total
        self.K, self.C = K[1:, 1:], C[1:, 1:]  # the drain node held at 0
        lam, phi = linalg.eigh(self.K, self.C)
        self.rates_tau = lam  # per unit tau
        start = self.C @ np.ones(M)  # phi^T C u(0), u(0) = 1 off the drain
        self.amplitude = phi.T @ start
        self.phi = phi
        self.mean_weight = (area[1:] @ phi) * self.amplitude / total

    @property
    def rates(self):
        """Per unit T_h."""
        return self.rates_tau * 4.0 * self.N ** 2

    def mean(self, T_h):
        return float(np.sum(self.mean_weight * np.exp(-self.rates * T_h)))

    def U(self, T_h):
        return 1.0 - self.mean(T_h)

    def pressure(self, rho, T_h):
        nodal = np.concatenate([[0.0], self.phi @ (self.amplitude * np.exp(-self.rates * T_h))])
        return np.interp(rho, self.r, nodal)


def surcharge_slab(nu, storage_ratio=1.0):
    """The coupling kappa of a thin slab under a surcharge (a free top, sigma_yy = -q uniform,
    rollers at r_w and r_e, u_r free; shear left out): eps_vol = (u - <u>) / (lambda + G) + (<u>
    - q) / E_oed, so the storage is (1 / (lambda + G) + n / K_w) u - (1 / (lambda + G) - 1 /
    E_oed) <u>. With storage_ratio = (1 / E_oed) / S (1 for incompressible water) kappa = (E_oed
    / (lambda + G) - 1) storage_ratio = (1 - 2 nu) / (1 - nu) storage_ratio (E_oed / (lambda + G) =
    2 (1 - nu))."""
    return (1.0 - 2.0 * nu) / (1.0 - nu) * storage_ratio


# --- the load's history ------------------------------------------------------------------------



def load_value(points, t):
    times = [p[0] for p in points]
    values = [p[1] for p in points]
    if t < times[0]:
        return 0.0
    return float(np.interp(t, times, values))


def superposed(weights, rates, points, t, scale):
    """sum_k w_k int_0^t dq(s) exp(-rate_k (t - s)) / scale for a piecewise-linear q(s) (its
    first value a step at its first time, held after its last): each mode's exponential integrated
    exactly over each segment. rates in 1/s."""
    if t <= 0.0:
        return 0.0
    total = np.zeros_like(rates)
    t0, q0 = points[0]
    if q0 != 0.0 and t > t0:
        total += q0 * np.exp(-rates * (t - t0))
    for (ta, qa), (tb, qb) in zip(points[:-1], points[1:]):
        if t <= ta:
            break
        slope = (qb - qa) / (tb - ta)
        end = min(tb, t)
        with np.errstate(over="ignore"):
            part = (np.exp(-rates * (t - end)) - np.exp(-rates * (t - ta))) / rates
        total += slope * part
    return float(np.sum(weights * total)) / scale


# --- the engine's cell -------------------------------------------------------------------------

class Cell:
    """A cell of the engine's parameters: r_w, r_e, H (m), the skeleton's E, nu, porosity n, the
    water's K_w and density, Darcy's k (m/s, under standard gravity) and the load history q(t)
    (Pa, compression positive, as points)."""

    def __init__(self, r_w, r_e, height, young, nu, porosity, water_bulk, conductivity,
                 water_density, load):
        self.r_w, self.r_e, self.H = float(r_w), float(r_e), float(height)
        self.N = self.r_e / self.r_w
        self.E, self.nu, self.n = float(young), float(nu), float(porosity)
        self.K_w, self.k, self.rho_w = float(water_bulk), float(conductivity), float(water_density)
        self.E_oed = self.E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))
        self.storage = 1.0 / self.E_oed + self.n / self.K_w
        self.B = (self.K_w / self.n) / (self.E_oed + self.K_w / self.n)
        self.c_h = self.k / (self.rho_w * STANDARD_GRAVITY * self.storage)
        self.load = list(load)
        self.q = self.load[-1][1]
        self.u0 = self.B * self.q
        self.area = 0.5 * (self.r_e ** 2 - self.r_w ** 2)  # per radian
        self.series = FreeStrain(self.N)
        self._fd = None

    def T_h(self, t):
        return self.c_h * t / (4.0 * self.r_e ** 2)

    def t_of(self, T_h):
        return T_h * 4.0 * self.r_e ** 2 / self.c_h

    def _series_modes(self, t):
        start = max(t - self.load[-1][0], 1e-3 * t) if t > 0 else 0.0
        w, c, a, rate = self.series.modes(self.series.terms_for(self.T_h(start)))
        return w, c, a, rate * self.c_h / (4.0 * self.r_e ** 2)

    def mean(self, t, model="free"):
        """The mean excess pore pressure (Pa) under the load's history: the free strain series,
        its finite-volume check ("fd") or the equal strain solution ("equal")."""
        if model == "free":
            w, _, _, rates = self._series_modes(t)
        elif model == "fd":
            if self._fd is None:
                self._fd = RadialFD(self.N)
            w, rates = self._fd.mean_weight, self._fd.rates * self.c_h / (4.0 * self.r_e ** 2)
        elif model == "equal":
            w = np.array([1.0])
            rates = np.array([8.0 / equal_strain_mu(self.N) * self.c_h / (4.0 * self.r_e ** 2)])
        else:
            raise ValueError(model)
        return self.B * superposed(w, rates, self.load, t, 1.0)

    def U(self, t, model="free"):
        return 1.0 - self.mean(t, model) / self.u0

    def pressure(self, r, t):
        """u(r, t) (Pa) of the free strain series under the load's history."""
        _, c, a, rates = self._series_modes(t)
        rho = np.atleast_1d(np.asarray(r, float)) / self.r_w
        return np.array([self.B * superposed(c * _z0(a * x, a), rates, self.load, t, 1.0)
                         for x in rho])

    def settlement(self, t, model="free"):
        """The top's settlement (m, down positive): H (q(t) - <u>) / E_oed."""
        return self.H * (load_value(self.load, t) - self.mean(t, model)) / self.E_oed

    def time_at(self, U, model="free"):
        """The time at which the reference reaches U (bisection in t)."""
        lo, hi = 0.0, self.t_of(0.05)
        while self.U(hi, model) < U:
            lo, hi = hi, 2.0 * hi
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.U(mid, model) < U else (lo, mid)
        return 0.5 * (lo + hi)


def from_case(case, text=""):
    """The cell of a parsed case: its soil, its extents and its load, from the rigid plate's
    force_y (a plate case) or from the lid case's load line (written by --write-lid). Returns
    (cell, info)."""
    if case.get("geometry", "axisymmetric") != "axisymmetric":
        raise ValueError("the cell is axisymmetric")
    name, m, body = coupled_soil(case)
    region = body["region"]
    r_w, r_e = region["r"]
    y0, y1 = region["y"]
    if y0 != 0.0:
        raise ValueError("the soil must stand on y = 0")
    drained = case.get("boundaries", {}).get("drained", [])
    if drained != ["r_min"] or case["grid"]["r"][0]["start"] != r_w:
        raise ValueError("the grid must start at r_w and drain there alone (drained = [\"r_min\"])")
    info = {"material": name, "soil": body["name"], "plate": None, "lid": None}
    area = 0.5 * (r_e ** 2 - r_w ** 2)
    plates = [b for b in case["bodies"] if "rigid" in b and "force_y" in b["rigid"]]
    if plates:
        plate = plates[0]
        force = load_points(plate["rigid"]["force_y"], f"bodies.{plate['name']}.rigid.force_y")
        load = [(t, (-f / area) or 0.0) for t, f in force]
        info["plate"] = plate["name"]
    else:
        lids = [p for p in case.get("prescribed", [])
                if "velocity_y" in p and p["nodes"].get("y") == y1 and "r" not in p["nodes"]]
        if len(lids) != 1:
            raise ValueError("a force-driven rigid plate, or one prescribed lid on the top, "
                             "expected")
        info["lid"] = lids[0]["name"]
        info["lid_velocity"] = load_points(lids[0]["velocity_y"], "lid")
        line = [ln for ln in text.splitlines() if ln.startswith(LOAD_TAG)]
        if not line:
            raise ValueError(f"the lid case has no load line ('{LOAD_TAG} ...'): write it with "
                             "--write-lid")
        import json
        load = [tuple(p) for p in json.loads(line[0][len(LOAD_TAG):])]
    porosity = 1.0 - m["density"] / m.get("grain_density", 2650.0)
    cell = Cell(r_w, r_e, y1, m["young_modulus"], m["poisson_ratio"], porosity,
                m.get("water_bulk_modulus", 2.2e9), m["hydraulic_conductivity"],
                m.get("water_density", 1000.0), load)
    if not cell.q > 0.0:
        raise ValueError("the load must press down")
    return cell, info


def read_case(path):
    import tomllib
    text = pathlib.Path(path).read_text()
    return tomllib.loads(text), text


# --- the lid case ------------------------------------------------------------------------------





def lid_case_text(plate_path, steps_per_rise=20, steps_after=160):
    """The lid variant of the plate case: the plate and its contact taken out, the soil's top line
    moved down with the series' settlement under the plate's load (its rise superposed) by a
    [[prescribed]] velocity_y, constant over each interval of a grid of times (20 over the rise,
    160 geometric to the end) and switched over 2e-7 s at each interval's end, so that the line's
    displacement is the series' at every interval's end."""
    import json

    case, text = read_case(plate_path)
    root = pathlib.Path(__file__).resolve().parent.parent
    try:
        plate_path = pathlib.Path(plate_path).resolve().relative_to(root).as_posix()
    except ValueError:
        pass
    cell, info = from_case(case, text)
    rise = cell.load[-1][0]
    end = sum(p["duration"] for p in case["phases"])
    times = np.concatenate([np.linspace(0.0, rise, steps_per_rise + 1),
                            np.geomspace(rise, end, steps_after + 1)[1:]])
    s = np.array([cell.settlement(t) for t in times])
    velocity = -np.diff(s) / np.diff(times)
    switch = 1e-7
    points = [(0.0, velocity[0])]
    for k in range(1, velocity.size):
        points.append((times[k] - switch, velocity[k - 1]))
        points.append((times[k] + switch, velocity[k]))
    points.append((times[-1], velocity[-1]))
    rows = ",\n".join(f"  [{t!r}, {v!r}]" for t, v in points)
    soil = case["materials"][info["material"]]
    body = [b for b in case["bodies"] if b["name"] == info["soil"]][0]
    grid_y = [z for z in case["grid"]["y"] if z["end"] <= cell.H]
    if not grid_y or grid_y[-1]["end"] != cell.H:
        raise ValueError("the plate case's grid must have a line at the soil's top")
    lines = [
        "# Radial consolidation towards a drain well (Barron 1948, free strain), the top moved",
        "# instead of pressed. Written by",
        f"#   tools/barron.py --write-lid {plate_path} <this file>",
        "# (do not edit by hand; tools/barron.py's docstring has the derivations). The soil, grid,",
        "# solver, phase and monitors are the plate case's; the plate and its contact are gone, and",
        "# the top line moves down with the settlement the free strain series gives under the",
        "# plate's load, H (q(t) - <u>(t)) / E_oed, its rise superposed: a [[prescribed]]",
        "# velocity_y, constant over each of 180 intervals (20 over the rise, 160 geometric to the",
        "# end). The top stays flat and frictionless (velocity_r free) and impermeable (a held DOF",
        "# holds the water too, and its support takes the water's reaction); under a flat top the",
        "# cell is one-dimensional in r and the series is exact, so the pore pressure must be the",
        "# series' (the lid's reaction, /boundaries/lid/F_y, is the held skeleton's alone: the",
        "# water the lid holds is not in it, docs/verification.md).",
        "#",
        f"#   build/release/bin/mpile run cases/verification/radial_consolidation.toml --threads 1 \\",
        "#       --out out/radial_consolidation",
        "#   tools/barron.py --compare out/radial_consolidation",
        f"{LOAD_TAG} {json.dumps([[t, q] for t, q in cell.load])}",
        'title = "Radial consolidation (Barron, free strain) under a lid moved as the series\' settlement"',
        'geometry = "axisymmetric"',
        "",
        "[grid]",
        f"r = {toml_value(case['grid']['r'])}",
        f"y = {toml_value(grid_y)}",
        "",
        f"[materials.{info['material']}]",
    ]
    lines += [f"{k} = {toml_value(v)}" for k, v in soil.items()]
    lines += ["", "[[bodies]]"] + [f"{k} = {toml_value(v)}" for k, v in body.items()]
    lines += ["", "[[prescribed]]", 'name = "lid"', f"nodes = {{ y = {cell.H!r} }}",
              f"velocity_y = {{ type = \"table\", points = [\n{rows}] }}", ""]
    lines += ["[boundaries]"] + [f"{k} = {toml_value(v)}" for k, v in case["boundaries"].items()]
    if case.get("solver"):
        lines += ["", "[solver]"] + [f"{k} = {toml_value(v)}" for k, v in case["solver"].items()]
    for phase in case["phases"]:
        lines += ["", "[[phases]]"] + [f"{k} = {toml_value(v)}" for k, v in phase.items()]
    output = dict(case.get("output", {}))
    monitors = output.pop("monitor", [])
    lines += ["", "[output]"] + [f"{k} = {toml_value(v)}" for k, v in output.items()]
    for monitor in monitors:
        lines += ["", "[[output.monitor]]"]
        lines += [f"{k} = {toml_value(v)}" for k, v in monitor.items()]
    return "\n".join(lines) + "\n"


# --- printing ----------------------------------------------------------------------------------

def describe(cell, info):
    kind = f"rigid plate '{info['plate']}'" if info["plate"] else f"lid '{info['lid']}'"
    return "\n".join([
        f"r_w = {cell.r_w:g} m, r_e = {cell.r_e:g} m (N = {cell.N:g}), H = {cell.H:g} m; "
        f"loaded by the {kind}: q = {cell.q:g} Pa, risen by t = {cell.load[-1][0]:g} s",
        f"E_oed = {cell.E_oed:.6g} Pa (E = {cell.E:.6g}, nu = {cell.nu:g}), n = {cell.n:.5f}, "
        f"K_w = {cell.K_w:.4g} Pa: B = {cell.B:.6f}, u0 = B q = {cell.u0:.6g} Pa",
        f"k = {cell.k:.6g} m/s: c_h = k / (gamma_w (1 / E_oed + n / K_w)) = {cell.c_h:.6g} m^2/s; "
        f"T_h = c_h t / (4 r_e^2) = {cell.T_h(1.0):.6g} t (t in s)",
        f"equal strain mu = {equal_strain_mu(cell.N):.6f}",
    ])


def reference_table(cell):
    rows = ["   t (s)     T_h   U free strain   U equal strain   U finite volume"]
    for T_h in (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5):
        t = cell.t_of(T_h)
        rows.append(f"{t:8.4f}  {T_h:6.3f}   {cell.U(t):13.5f}   {cell.U(t, 'equal'):14.5f}   "
                    f"{cell.U(t, 'fd'):15.5f}")
    rows.append("(the load's rise superposed; times after it)")
    for U in U_LEVELS:
        t = cell.time_at(U)
        rows.append(f"free strain U = {U}: t = {t:.5f} s, T_h = {cell.T_h(t):.5f}")
    return "\n".join(rows)




class GridFV:
    """The engine's grid's own scheme without its particles: one pore pressure per cell of a
    uniform radial grid (cells [r_i, r_i+1], r_0 = r_w), the water's Darcy velocity at each node
    from the neighbouring cells' pressures over the lumped drag (int N_i r dr: h r_i inside, r_w
    h / 2 + h^2 / 6 at the drain node, where p = 0 beyond the face gives the gradient p_1 over that
    length, the natural condition of the engine's water force), held at r_e; each cell's storage
    from the fluxes through its nodes (physics.md 9b, with B-bar's cell mean). Under the lid the
    cell's vertical strain is prescribed (its mean volumetric strain; the radial part (u - <u>) /
    E_oed), under a plate the force. Crank-Nicolson in time, 20 steps over the load's rise and
    steps of at most 1e-3 of the run after it. What the particles' transfers add is the run's
    difference from this."""

    def __init__(self, cell, cells):
        self.cell = cell
        M = int(cells)
        r = np.linspace(cell.r_w, cell.r_e, M + 1)
        h = r[1] - r[0]
        self.r, self.h = r, h
        self.area = 0.5 * (r[1:] ** 2 - r[:-1] ** 2)
        K = np.zeros((M, M))
        for i in range(1, M):
            c = r[i] / h  # r_i^2 / (h r_i)
            K[i - 1, i - 1] += c
            K[i, i] += c
            K[i - 1, i] -= c
            K[i, i - 1] -= c
        self.drain_length = r[0] * h / 2.0 + h * h / 6.0
        K[0, 0] += r[0] ** 2 / self.drain_length
        self.K = cell.k / (cell.rho_w * STANDARD_GRAVITY) * K

    def means(self, times, lid_velocity=None):
        """The mean excess pore pressure (Pa) at `times` (sorted), under the lid's velocity table
        (points) or, without one, under the cell's load."""
        cell, a = self.cell, self.area
        total = a.sum()
        if lid_velocity is not None:
            C = cell.storage * np.diag(a) - np.outer(a, a) / total / cell.E_oed
        else:
            C = cell.storage * np.diag(a)
        rise = cell.load[-1][0]
        end = float(times[-1])
        steps = np.concatenate([np.linspace(0.0, rise, 21),
                                np.arange(rise, end, max(min(1e-3 * end, 1e-3), 1e-9))[1:], [end]])
        steps = np.unique(np.concatenate([steps, np.asarray(times, float)]))
        p = np.zeros(a.size)
        out = []
        k = 0
        strain = (lambda t: integrate_points(lid_velocity, t) / cell.H) if lid_velocity else None
        for t0, t1 in zip(steps[:-1], steps[1:]):
            dt = t1 - t0
            if strain is not None:
                source = -a * (strain(t1) - strain(t0))  # eps_yy (tension +) falls: water out
            else:
                source = a * (load_value(cell.load, t1) - load_value(cell.load, t0)) / cell.E_oed
            p = np.linalg.solve(C + 0.5 * dt * self.K, (C - 0.5 * dt * self.K) @ p + source)
            while k < len(times) and times[k] <= t1 + 1e-12:
                out.append(float(a @ p / total))
                k += 1
        return np.array(out)


def run_series(run):
    """From a run: its cell and info, the snapshots' times, mean excess pore pressures (Pa,
    compression positive) and the snapshots themselves, its history (times, the lid's reaction or
    the plate's settlement, monitors) and its case as it ran."""
    import h5py
    import tomllib

    mpile = mpile_package()
    path = pathlib.Path(run)
    history = path / "history.h5" if path.is_dir() else path
    with h5py.File(history, "r", locking=False) as f:
        text = f.attrs["case_text"]
        resolved = f.attrs.get("case_resolved", text)
        text = text.decode() if isinstance(text, bytes) else str(text)
        resolved = resolved.decode() if isinstance(resolved, bytes) else str(resolved)
        attrs = {k: f.attrs[k] for k in ("status", "wall_time") if k in f.attrs}
        steps = int(f["step"][-1]) if "step" in f else None
        # The ledger's largest relative residual after step 100 (the first steps' energies are
        # too small for a ratio to mean anything).
        late = f["step"][:] > 100
        residual = np.abs(f["energy/relative_residual"][:])
        residual_peak = float(residual[late].max()) if late.any() else float("nan")
    case = tomllib.loads(resolved)
    cell, info = from_case(case, text)
    snaps = mpile.open_snapshots(history.parent)
    times, means = [], []
    for t, snap in zip(snaps.times, snaps):
        soil = soil_particles(snap, info)
        volume = snap.arrays["volume"][soil]
        excess = -snap.arrays["excess_pore_pressure"][soil]
        times.append(t)
        means.append(float(np.sum(volume * excess) / np.sum(volume)))
    ds = mpile.open_history(history)
    hist = {"time": ds["time"].values, "dt": ds["dt"].values, "steps": steps,
            "residual_peak": residual_peak}
    hist.update({k: (v.decode() if isinstance(v, bytes) else v) for k, v in attrs.items()})
    if info["lid"]:
        hist["F_y"] = ds[f"boundaries/{info['lid']}/F_y"].values
    if info["plate"]:
        hist["u_y"] = ds[f"bodies/{info['plate']}/u_y"].values
    hist["monitors"] = {}
    for name in sorted({v.split("/")[1] for v in ds.data_vars if v.startswith("monitors/")}):
        hist["monitors"][name] = {k: ds[f"monitors/{name}/{k}"].values
                                  for k in ("excess_pore_pressure", "r", "y")
                                  if f"monitors/{name}/{k}" in ds}
    return cell, info, np.array(times), np.array(means), snaps, hist, case


def soil_particles(snap, info):
    """The soil body's particles of a snapshot (a plate's are left out)."""
    return snap.arrays["body"] == list(snap.body_names).index(info["soil"])


def grid_cells(case):
    zones = case["grid"]["r"]
    if len(zones) != 1:
        raise ValueError("one uniform zone along r expected")
    return int(zones[0]["cells"])


def compare(run, profile=True):
    """Prints the run against the references; returns {(U, source): run - series}."""
    cell, info, times, means, snaps, hist, case = run_series(run)
    print(describe(cell, info))
    solver = case.get("solver", {})
    scheme = "implicit" if solver.get("implicit_pore_pressure") else "explicit"
    cells = grid_cells(case)
    rows = sum(z["cells"] for z in case["grid"]["y"] if z["end"] <= cell.H)
    print(f"run: {run}: {cells} x {rows}"
          f" cells, the {scheme} pore pressure, Courant number {solver.get('courant_number', 0.8)}"
          f"; {hist.get('steps')} steps, {float(hist.get('wall_time', float('nan'))):.1f} s wall; "
          f"status: {hist.get('status', '')}")
    U_p = 1.0 - means / cell.u0
    sources = [("pore pressure", times, U_p)]
    t_h = hist["time"]
    if info["plate"]:
        s = -hist["u_y"]
        q_t = np.array([load_value(cell.load, t) for t in t_h])
        sources.append(("settlement", t_h, 1.0 - (q_t - cell.E_oed * s / cell.H) / cell.u0))
    levels = [(U, cell.time_at(U)) for U in U_LEVELS]
    levels = [(U, t) for U, t in levels if t <= times[-1]]
    sample = list(np.geomspace(cell.t_of(0.002), times[-1], 12))
    fv_times = sorted(set(sample + [t for _, t in levels]))
    fv = GridFV(cell, cells).means(np.array(fv_times), info.get("lid_velocity"))
    fv_U = dict(zip(fv_times, 1.0 - fv / cell.u0))
    print("U against the free strain series; 'grid' is the engine's grid's own finite volume "
          "scheme without particles (GridFV), the floor of the grid's error:")
    print("   t (s)     T_h  " + "".join(f"{name:>15s}" for name, _, _ in sources)
          + "    free strain   equal strain           grid")
    for t in sample:
        row = f"{t:8.4f}  {cell.T_h(t):6.4f}  "
        row += "".join(f"{np.interp(t, ts, us):15.4f}" for _, ts, us in sources)
        row += f"{cell.U(t):15.4f}{cell.U(t, 'equal'):15.4f}{fv_U[t]:15.4f}"
        print(row)
    print("differences in U from the series where it has U = 0.2, 0.5, 0.8 (run, and the grid's "
          "own scheme):")
    results = {}
    for U, t in levels:
        line = f"U = {U}: t = {t:.4f} s (T_h = {cell.T_h(t):.4f}):"
        for name, ts, us in sources:
            d = float(np.interp(t, ts, us)) - U
            results[(U, name)] = d
            line += f" {name} {d:+.4f};"
        results[(U, "grid")] = fv_U[t] - U
        line += f" grid {fv_U[t] - U:+.4f}; equal strain there {cell.U(t, 'equal') - U:+.4f}"
        print(line)
    if info["lid"]:
        # The lid's recorded reaction holds the skeleton and the water the lid keeps to it (the
        # support's reaction includes the water's share since 3f431e6; before, it read 0.79 of the
        # load at U = 0.2). The lid moves as the series settles, so where the run consolidates more
        # slowly than the series its excess pore pressure adds to the load: the ratio exceeds 1 by
        # about B (U_series - U_run).
        after = t_h > 2.0 * cell.load[-1][0]
        ratio = hist["F_y"] / (-cell.q * cell.area)
        print(f"lid's reaction /boundaries/{info['lid']}/F_y over -q A = {-cell.q * cell.area:.6g} "
              f"N/rad after twice the rise: {ratio[after].min():.4f} to {ratio[after].max():.4f}")
        for U, t in levels:
            k = int(np.argmin(np.abs(t_h - t)))
            print(f"  at U = {U}: {ratio[k]:.4f}")
    if profile:
        print_profile(cell, info, case, snaps, times, levels)
        print_monitors(cell, hist, levels)
    print(f"energy ledger: largest relative residual after step 100 {hist['residual_peak']:.4%}; "
          f"status {hist.get('status', '')}")
    results["residual"] = hist["residual_peak"]
    results["complete"] = str(hist.get("status", "")).startswith("complete")
    return results


def check(results, expect):
    """The run's results against the bounds asked for (--expect NAME=BOUND): 'U0.2', 'U0.5',
    'U0.8' the pore pressure's |U - U_series| where the series has that U (the run must reach
    it), 'residual' the ledger's largest relative residual after step 100. Returns the failures."""
    failures = [] if results.get("complete") else ["the run did not complete"]
    for name, bound in expect.items():
        if name == "residual":
            measured = results["residual"]
        else:
            measured = abs(results.get((float(name[1:]), "pore pressure"), float("inf")))
        if not measured <= bound:
            failures.append(f"{name} {measured:.4g} > {bound:g}")
    return failures


def cell_table(cell, info, case, snaps):
    """Per radial cell (the soil's particles binned by their initial r), each snapshot's volume
    and volume-weighted excess pore pressure."""
    M = grid_cells(case)
    h = (cell.r_e - cell.r_w) / M
    first = snaps[0]
    soil = soil_particles(first, info)
    order0 = np.argsort(first.arrays["id"][soil])
    column = np.clip(np.floor((first.positions[soil][order0, 0] - cell.r_w) / h).astype(int), 0,
                     M - 1)
    volumes, pressures = [], []
    for snap in snaps:
        soil = soil_particles(snap, info)
        order = np.argsort(snap.arrays["id"][soil])
        if order.size != column.size:
            raise ValueError("the particles changed in number: cannot follow the cells")
        V = snap.arrays["volume"][soil][order]
        u = -snap.arrays["excess_pore_pressure"][soil][order]
        Vc = np.bincount(column, weights=V, minlength=M)
        volumes.append(Vc)
        pressures.append(np.bincount(column, weights=V * u, minlength=M) / Vc)
    return M, h, np.array(volumes), np.array(pressures)


def print_profile(cell, info, case, snaps, times, levels):
    """The cells' pore pressures against the series' cell means, and each node's water flux (from
    the cells' water balance: the water gone from the cells beyond it) over the Darcy flux of the
    neighbouring cells' pressures (the grid's own scheme's): where the run departs first."""
    M, h, volumes, pressures = cell_table(cell, info, case, snaps)
    V0 = volumes[0]
    drained = -(volumes / V0 - 1.0) * V0 - cell.n * pressures / cell.K_w * V0
    rate = np.gradient(drained, times, axis=0)
    mobility = cell.k / (cell.rho_w * STANDARD_GRAVITY)
    r = cell.r_w + h * np.arange(M + 1)
    length = r * h
    length[0] = cell.r_w * h / 2.0 + h * h / 6.0
    gauss = (np.array([-0.7745966692414834, 0.0, 0.7745966692414834]),
             np.array([5.0, 8.0, 5.0]) / 9.0)
    for U, t in levels[:2]:
        k = int(np.argmin(np.abs(times - t)))
        tk = times[k]
        flux = np.cumsum(rate[k][::-1])[::-1]  # through node i, towards the drain
        difference = np.concatenate([[pressures[k][0]], np.diff(pressures[k])])
        darcy = mobility * cell.H * r[:M] ** 2 * difference / length[:M]
        print(f"t = {tk:.4f} s (the series' U = {cell.U(tk):.4f}): by cell, the excess pore "
              "pressure (Pa) against the series' cell mean, and the water's flux through the cell's"
              " inner node over its Darcy flux:")
        print("   cell      r         run      series   (run - series) / u0    flux / Darcy")
        rows = list(range(min(M, 6))) + list(range(6, M, max(1, M // 6)))
        for c in rows:
            points = r[c] + 0.5 * h * (1.0 + gauss[0])
            values = cell.pressure(points, tk)
            series = np.sum(gauss[1] * values * points) / np.sum(gauss[1] * points)
            print(f"  {c:5d} {r[c]:6.3f}-{r[c + 1]:5.3f} {pressures[k][c]:9.1f} {series:10.1f}"
                  f" {(pressures[k][c] - series) / cell.u0:+17.4f} {flux[c] / darcy[c]:15.3f}")


def print_monitors(cell, hist, levels):
    if not hist["monitors"]:
        return
    print("monitors: excess pore pressure / u0, run (series), where the series has U =",
          ", ".join(str(U) for U, _ in levels))
    for name, m in hist["monitors"].items():
        if "excess_pore_pressure" not in m:
            continue
        r = float(m["r"][0]) if "r" in m else float("nan")
        row = f"  {name:>14s} (r = {r:.4f}):"
        for U, t in levels:
            run = -np.interp(t, hist["time"], m["excess_pore_pressure"]) / cell.u0
            ref = float(cell.pressure(r, t)[0]) / cell.u0
            row += f"  {run:.4f} ({ref:.4f})"
        print(row)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--case", help="a radial consolidation case: its references at a few times")
    what.add_argument("--compare", metavar="RUN_DIR", help="a run's directory (or its history.h5)")
    what.add_argument("--write-lid", nargs=2, metavar=("PLATE_CASE", "LID_CASE"),
                      help="write the lid case from the plate case")
    parser.add_argument("--no-profile", action="store_true", help="--compare: U only")
    parser.add_argument("--expect", action="append", default=[], metavar="NAME=BOUND",
                        help="with --compare: fail (exit 1) unless NAME (U0.2, U0.5, U0.8: the pore "
                             "pressure's |U - U_series| where the series has that U; residual: "
                             "the ledger's largest relative residual after step 100) is at most "
                             "BOUND")
    args = parser.parse_args()
    if args.case:
        case, text = read_case(args.case)
        cell, info = from_case(case, text)
        print(describe(cell, info))
        print(reference_table(cell))
    elif args.write_lid:
        text = lid_case_text(args.write_lid[0])
        pathlib.Path(args.write_lid[1]).write_text(text)
        print(f"wrote {args.write_lid[1]}")
    else:
        results = compare(args.compare, profile=not args.no_profile)
        if args.expect:
            return expect_check("barron", args.expect, ("U0.2", "U0.5", "U0.8", "residual"), check,
                                results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
