#!/usr/bin/python3
"""Mandel's problem: the closed form, and a run of cases/verification/mandel_plate.toml against it.

  tools/mandel.py --case cases/verification/mandel_plate.toml   # the reference at a few times
  tools/mandel.py --compare out/mandel_plate                    # a run against it
  tools/mandel.py --write-lid cases/verification/mandel_plate.toml cases/verification/mandel_lid.toml
  tools/mandel.py --compare out/mandel_lid   # its force: --load-from PLATE_CASE (default the above)

A saturated poroelastic slab -a <= x <= a, -b <= y <= b in plane strain, squeezed between two
rigid, frictionless, impermeable plates by a force 2F per unit length applied at t = 0+ and held,
its faces x = +-a traction-free and drained (p = 0). Mandel (1953); the series as Cheng and
Detournay (1988, Int. J. Numer. Anal. Methods Geomech. 12, 551-572) and Abousleiman, Cheng, Cui,
Detournay and Roegiers (1996, Geotechnique 46(2), 187-195) give it, with G the shear modulus, nu
and nu_u the drained and undrained Poisson ratios, B Skempton's coefficient, c the consolidation
coefficient and alpha_n the positive roots of tan(alpha) = (1 - nu) / (nu_u - nu) alpha:

  p(x, t)      = 2 p0 sum sin(a_n) / (a_n - sin a_n cos a_n) (cos(a_n x / a) - cos a_n) e_n
  sigma_yy     = -F / a - 2 F (nu_u - nu) / (a (1 - nu)) sum sin a_n / D_n cos(a_n x / a) e_n
                 + 2 F / a sum sin a_n cos a_n / D_n e_n
  u_y(y, t)    = [-F (1 - nu) / (2 G a) + F (1 - nu_u) / (G a) sum sin a_n cos a_n / D_n e_n] y
  u_x(x, t)    = [F nu / (2 G a) - F nu_u / (G a) sum sin a_n cos a_n / D_n e_n] x
                 + F / G sum cos a_n / D_n sin(a_n x / a) e_n

with D_n = a_n - sin a_n cos a_n, e_n = exp(-a_n^2 c t / a^2) and p0 = F B (1 + nu_u) / (3 a), the
undrained pore pressure (compression positive here; sigma tension positive). F is the force on
the half-width a, the quarter model's plate: the whole slab carries 2F.

From the engine's parameters (docs/physics.md sections 9a, 9b: grains incompressible, so Biot's
alpha = 1 and the Biot modulus M = K_w / n): K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)),
K_u = K + K_w / n, B = (K_w / n) / K_u, nu_u = (3 K_u - 2 G) / (2 (3 K_u + G)); Darcy's k (m/s,
measured under standard gravity, engine/materials/pore_water.hpp) is a mobility k / (rho_w g0),
g0 = 9.80665 m/s^2, and c = (k / (rho_w g0)) / (n / K_w + 1 / (K + 4 G / 3)), T = a^2 / c.

The roots are bracketed one per interval ((n - 1) pi, (n - 1/2) pi) (the first in (0, pi/2): the
slope (1 - nu) / (nu_u - nu) exceeds 1 since nu_u < 1) and bisected to rounding. A step response at
c t / a^2 = tau takes sqrt(45 / tau) / pi + 2 terms (the first left out below e^-45 of the first);
at t = 0+ it is the undrained closed form. The run's load rises over a time: --compare superposes
the closed form over the drive's own history (exactly, each term's exponential integrated over the
piecewise-linear load), as the V10 comparison does, and prints the step's values beside it.
tests/mandel_test.py checks the series against facts it must satisfy and against the Laplace
transform of the governing equations, inverted numerically.
"""
import argparse
import math
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from case_history import (coupled_soil, expect_check, integrate_points, load_points,  # noqa: E402
                          mpile_package, toml_value)

STANDARD_GRAVITY = 9.80665  # engine/materials/pore_water.hpp: k is measured under it
SUPERPOSITION_TERMS = 4000  # the ramp's terms fall as 1/n^3: 4000 leave < 1e-8 of F
DEFAULT_PLATE_CASE = "cases/verification/mandel_plate.toml"


def mandel_roots(nu, nu_u, count):
    """The first `count` positive roots of tan(x) = (1 - nu) / (nu_u - nu) x, by bisection of
    sin x - A x cos x on ((n - 1) pi, (n - 1/2) pi) (the first on (0, pi/2), where the function
    starts at (1 - A) x < 0): exactly one root per interval for A > 1."""
    if not nu_u > nu:
        raise ValueError(f"Mandel's problem needs nu_u > nu (B > 0), got nu = {nu}, nu_u = {nu_u}")
    slope = (1.0 - nu) / (nu_u - nu)
    if not slope > 1.0:
        raise ValueError(f"(1 - nu) / (nu_u - nu) = {slope} must exceed 1 (nu_u < 1)")
    n = np.arange(1, count + 1, dtype=float)
    lo = (n - 1.0) * np.pi
    hi = (n - 0.5) * np.pi
    sign_hi = np.sign(np.sin(hi))
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        value = np.sin(mid) - slope * mid * np.cos(mid)
        upper = np.sign(value) == sign_hi
        hi = np.where(upper, mid, hi)
        lo = np.where(upper, lo, mid)
    roots = 0.5 * (lo + hi)
    # Check: inside its bracket, bisected to adjacent doubles, and the equation to rounding: the
    # residual within a few ulps of x times the slope there, |d/dx (sin x - A x cos x)| <= 1 + A x
    # (plus the rounding of A x cos x itself, A x eps).
    if not (np.all(roots > (n - 1.0) * np.pi) and np.all(roots < (n - 0.5) * np.pi)):
        raise ArithmeticError("a root left its bracket")
    eps = np.finfo(float).eps
    if np.any(hi - lo > 4.0 * eps * hi):
        raise ArithmeticError("bisection did not converge")
    residual = np.abs(np.sin(roots) - slope * roots * np.cos(roots))
    if np.any(residual > 8.0 * eps * (1.0 + slope * roots) * (1.0 + roots)):
        raise ArithmeticError(f"roots not converged: residual {residual.max():.3g}")
    return roots


class Mandel:
    """Mandel's problem for the slab's half-width a, half-height b (the quarter model's extents)
    and a force F on the half-width (2F on the slab), per unit length. Pressures compression
    positive, stresses tension positive, displacements along +x and +y."""

    def __init__(self, shear_modulus, nu, nu_u, skempton_b, consolidation, a, b, force):
        self.G, self.nu, self.nu_u, self.B = shear_modulus, nu, nu_u, skempton_b
        self.c, self.a, self.b, self.F = consolidation, a, b, force
        self._roots = mandel_roots(nu, nu_u, 64)

    @classmethod
    def from_engine(cls, young, nu, porosity, water_bulk, conductivity, water_density, a, b, force):
        """From the engine's parameters: the skeleton's E and nu, the porosity n, K_w, Darcy's k
        (m/s) and rho_w; incompressible grains (alpha = 1, M = K_w / n)."""
        G = young / (2.0 * (1.0 + nu))
        K = young / (3.0 * (1.0 - 2.0 * nu))
        M = water_bulk / porosity
        K_u = K + M
        B = M / K_u
        nu_u = (3.0 * K_u - 2.0 * G) / (2.0 * (3.0 * K_u + G))
        mobility = conductivity / (water_density * STANDARD_GRAVITY)
        c = mobility / (1.0 / M + 1.0 / (K + 4.0 * G / 3.0))
        model = cls(G, nu, nu_u, B, c, a, b, force)
        model.K, model.K_u, model.M, model.mobility = K, K_u, M, mobility
        model.water_density = water_density
        return model

    @property
    def p0(self):
        """The undrained pore pressure F B (1 + nu_u) / (3 a), uniform at t = 0+."""
        return self.F * self.B * (1.0 + self.nu_u) / (3.0 * self.a)

    @property
    def T(self):
        """a^2 / c (s)."""
        return self.a**2 / self.c

    def roots(self, count):
        if count > self._roots.size:
            self._roots = mandel_roots(self.nu, self.nu_u, max(count, 2 * self._roots.size))
        return self._roots[:count]

    @staticmethod
    def terms_for(tau):
        """Terms a step response at c t / a^2 = tau needs: the first left out has e^{-a^2 tau}
        below e^-45 (a_n > (n - 1) pi)."""
        return int(math.ceil(math.sqrt(45.0 / tau) / math.pi)) + 2

    # Each quantity per unit force as C0 + sum C_n exp(-lambda_n t), lambda_n = a_n^2 c / a^2.
    def _coefficients(self, quantity, where, count):
        al = self.roots(count)
        s, co = np.sin(al), np.cos(al)
        d = al - s * co
        a, G, nu, nu_u = self.a, self.G, self.nu, self.nu_u
        if quantity == "p":
            c0 = 0.0
            cn = 2.0 * self.p0 / self.F * s / d * (np.cos(al * where / a) - co)
        elif quantity == "sigma_yy":
            c0 = -1.0 / a
            cn = (-2.0 * (nu_u - nu) / (a * (1.0 - nu)) * s / d * np.cos(al * where / a)
                  + 2.0 / a * s * co / d)
        elif quantity == "u_y":
            c0 = -(1.0 - nu) * where / (2.0 * G * a)
            cn = (1.0 - nu_u) * where / (G * a) * s * co / d
        elif quantity == "u_x":
            c0 = nu * where / (2.0 * G * a)
            cn = -nu_u * where / (G * a) * s * co / d + co / d * np.sin(al * where / a) / G
        else:
            raise ValueError(f"unknown quantity {quantity}")
        return c0, cn, al**2 * self.c / a**2

    def undrained(self, quantity, where):
        """The value at t = 0+ for the force F (the undrained elastic response, nu_u)."""
        F, a, G = self.F, self.a, self.G
        if quantity == "p":
            return self.p0 if where < a else 0.0
        if quantity == "sigma_yy":
            return -F / a
        if quantity == "u_y":
            return -F * (1.0 - self.nu_u) * where / (2.0 * G * a)
        if quantity == "u_x":
            return F * self.nu_u * where / (2.0 * G * a)
        raise ValueError(f"unknown quantity {quantity}")

    def step(self, quantity, where, t):
        """The quantity at x (p, sigma_yy, u_x) or y (u_y) and time t after the force F was
        applied at t = 0 (t = 0: the undrained value, t = 0+)."""
        if t < 0.0:
            return 0.0
        if t == 0.0:
            return self.undrained(quantity, where)
        tau = self.c * t / self.a**2
        c0, cn, lam = self._coefficients(quantity, where, self.terms_for(tau))
        return self.F * (c0 + np.sum(cn * np.exp(-lam * t)))

    def loaded(self, quantity, where, t, load):
        """The same under a force history: `load` the points (t_j, F_j) of a piecewise-linear
        force, zero before the first time unless F_0 is not (then a step to F_0 there), held at the
        last value after the last. Each term is integrated exactly over each segment; a step
        (the load's jumps) contributes its step response. Scaled by the history's own values, not
        by self.F."""
        times = np.array([p[0] for p in load], float)
        values = np.array([p[1] for p in load], float)
        c0, cn, lam = self._coefficients(quantity, where, SUPERPOSITION_TERMS)
        total = 0.0
        if values[0] != 0.0 and t >= times[0]:  # a jump at the first point: its step response
            total += values[0] * self.step(quantity, where, t - times[0]) / self.F
        for j in range(len(times) - 1):
            t0, t1 = times[j], times[j + 1]
            if t <= t0:
                break
            dv = values[j + 1] - values[j]
            if t1 == t0:  # a jump
                total += dv * self.step(quantity, where, t - t0) / self.F
                continue
            rate = dv / (t1 - t0)
            end = min(t, t1)
            # exp(-lam (t - end)) - exp(-lam (t - t0)), without cancelling for a short segment
            decay = -np.exp(-lam * (t - end)) * np.expm1(-lam * (end - t0))
            total += rate * (c0 * (end - t0) + np.sum(cn * decay / lam))
        return total

    def pressure(self, x, t):
        return self.step("p", x, t)

    def sigma_yy(self, x, t):
        return self.step("sigma_yy", x, t)

    def settlement(self, t):
        """The plate's settlement, -u_y(b, t) (positive downward), for the force F."""
        return -self.step("u_y", self.b, t)

    def u_x(self, x, t):
        return self.step("u_x", x, t)

    def stored_energy(self, t, load, points=401):
        """The quarter's stored energy (J per unit length) at t under the force history `load`:
        (1/2) integral (sigma : eps + p zeta) dV (Biot), with sigma_xx = 0, eps_yy = eps(t) uniform
        and fields of x alone: (1/2) (F(t) delta(t) + b integral_0^a p zeta dx), zeta = eps_xx +
        eps + p / M the water's content, eps_xx = (p - lambda eps) / (2 G + lambda) (simpson in x)."""
        lam = 2.0 * self.G * self.nu / (1.0 - 2.0 * self.nu)
        eps = self.loaded("u_y", self.b, t, load) / self.b
        x = np.linspace(0.0, self.a, points)
        p = np.array([self.loaded("p", xx, t, load) for xx in x])
        zeta = (p - lam * eps) / (2.0 * self.G + lam) + eps + p / self.M
        force = np.interp(t, [q[0] for q in load], [q[1] for q in load])
        w = np.ones(points)
        w[1:-1:2], w[2:-1:2] = 4.0, 2.0
        integral = np.sum(w * p * zeta) * (x[1] - x[0]) / 3.0
        return 0.5 * (force * (-eps * self.b) + self.b * integral)

    def work(self, times, load):
        """The force's work on the quarter, integral F d(delta), at each of the increasing
        `times` (trapezoidal in the times given, from 0)."""
        times = np.concatenate([[0.0], np.asarray(times, float)])
        delta = np.array([-self.loaded("u_y", self.b, t, load) for t in times])
        force = np.interp(times, [q[0] for q in load], [q[1] for q in load])
        return np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(delta))

    def peak_centre_pressure(self):
        """The largest p(0, t) / p0 and its c t / a^2 (a golden-section search around the grid's
        maximum)."""
        taus = np.logspace(-4, 1, 400)
        values = [self.pressure(0.0, tau * self.T) for tau in taus]
        k = int(np.argmax(values))
        lo, hi = taus[max(k - 1, 0)], taus[min(k + 1, taus.size - 1)]
        g = (math.sqrt(5.0) - 1.0) / 2.0
        f = lambda tau: -self.pressure(0.0, tau * self.T)
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        f1, f2 = f(x1), f(x2)
        for _ in range(80):
            if f1 < f2:
                hi, x2, f2 = x2, x1, f1
                x1 = hi - g * (hi - lo)
                f1 = f(x1)
            else:
                lo, x1, f1 = x1, x2, f2
                x2 = lo + g * (hi - lo)
                f2 = f(x2)
        tau = 0.5 * (lo + hi)
        return self.pressure(0.0, tau * self.T) / self.p0, tau


# --- the case ---------------------------------------------------------------------------------



def from_case(case, load_case=None):
    """The closed form for a case (a parsed TOML dict): its coupled material, the soil body's
    extents (a, b) and the force-driven rigid plate (F, its history). A lid case (the top's motion
    prescribed, no plate: --write-lid) takes its force history from `load_case`, the plate case it
    was made from. Returns (model, info)."""
    if case.get("geometry") != "plane_strain":
        raise ValueError("Mandel's problem is plane strain: the case's geometry is "
                         f"{case.get('geometry', 'axisymmetric')!r}")
    name, m, soil_body = coupled_soil(case)
    porosity = 1.0 - m["density"] / m.get("grain_density", 2650.0)
    bodies = case["bodies"]
    soil = [soil_body]
    plates = [body for body in bodies if "rigid" in body and "force_y" in body["rigid"]]
    region = soil[0]["region"]
    if "r" not in region or region["r"][0] != 0.0 or region["y"][0] != 0.0:
        raise ValueError("the soil must be the rectangle [0, a] x [0, b]")
    a, b = region["r"][1], region["y"][1]
    info = {"material": name, "soil": soil[0]["name"], "porosity": porosity, "plate": None,
            "lid": None}
    if len(plates) == 1:
        plate = plates[0]
        load = load_points(plate["rigid"]["force_y"], f"bodies.{plate['name']}.rigid.force_y")
        info["plate"] = plate["name"]
        info["drive_phase"] = plate["rigid"].get("phase")
    else:
        lids = [p for p in case.get("prescribed", [])
                if "velocity_y" in p and p["nodes"].get("y") == b and "r" not in p["nodes"]]
        if len(plates) or len(lids) != 1:
            raise ValueError("one force-driven rigid plate, or one prescribed lid on y = b, expected")
        if load_case is None:
            raise ValueError("a lid case's force is its plate case's: give it (--load-from)")
        plate_model, plate_info = from_case(load_case)
        load = [(t, -v) for t, v in plate_info["load"]]
        lid = lids[0]
        info["lid"] = lid["name"]
        info["lid_velocity"] = load_points(lid["velocity_y"], f"prescribed.{lid['name']}.velocity_y")
        info["drive_phase"] = lid.get("phase")
    force = -load[-1][1]  # the drive pushes down (negative force_y); F is its magnitude
    if not force > 0.0:
        raise ValueError("the plate's force must push down (force_y < 0)")
    model = Mandel.from_engine(m["young_modulus"], m["poisson_ratio"], porosity,
                               m.get("water_bulk_modulus", 2.2e9), m["hydraulic_conductivity"],
                               m.get("water_density", 1000.0), a, b, force)
    info["load"] = [(t, -v) for t, v in load]
    if info["lid"] is not None:
        plate_model = from_case(load_case)[0]
        for key in ("G", "nu", "nu_u", "B", "c", "a", "b"):
            if not math.isclose(getattr(model, key), getattr(plate_model, key), rel_tol=1e-12):
                raise ValueError(f"the lid case's {key} is not its plate case's")
    return model, info






def lid_case_text(plate_path, steps_per_rise=40, steps_after=120):
    """The lid variant of a plate case: the plate and its contact taken out, the soil's top line
    y = b moved down with the closed form's settlement of the plate case (its force's rise
    superposed) by a [[prescribed]] velocity_y. The velocity is constant over each interval of a
    grid of times (40 over the rise, 120 spaced geometrically to the phase's end), the
    displacement's increment over it divided by its length, switched over 2e-7 s at each interval's
    end (symmetric: the displacement at every grid time is the closed form's to rounding)."""
    import tomllib

    text = pathlib.Path(plate_path).read_text()
    case = tomllib.loads(text)
    root = pathlib.Path(__file__).resolve().parent.parent
    try:  # named from the repository's root when it lies in it, as the header's commands run
        plate_path = pathlib.Path(plate_path).resolve().relative_to(root).as_posix()
    except ValueError:
        pass
    model, info = from_case(case)
    load = info["load"]  # the force F(t) pressing down, positive
    rise = load[-1][0]
    end = sum(p["duration"] for p in case["phases"])
    times = np.concatenate([np.linspace(0.0, rise, steps_per_rise + 1),
                            np.geomspace(rise, end, steps_after + 1)[1:]])
    uy = np.array([model.loaded("u_y", model.b, t, load) for t in times])
    velocity = np.diff(uy) / np.diff(times)
    switch = 1e-7
    points = [(0.0, velocity[0])]
    for k in range(1, velocity.size):
        points.append((times[k] - switch, velocity[k - 1]))
        points.append((times[k] + switch, velocity[k]))
    points.append((times[-1], velocity[-1]))
    rows = ",\n".join(f"  [{t!r}, {v!r}]" for t, v in points)
    soil_name = info["material"]
    soil = case["materials"][soil_name]
    body = [b for b in case["bodies"] if b["name"] == info["soil"]][0]
    lines = [
        "# Mandel's problem with the top moved instead of pressed: the closest the case format comes",
        "# to the rigid plate without a rigid body. Written by",
        f"#   tools/mandel.py --write-lid {plate_path} <this file>",
        "# (do not edit by hand). The soil, grid, solver, phase and monitors are the plate case's;",
        "# the plate and its contact are gone, and the grid line y = b moves down as the",
        "# closed form's plate does under the plate case's force (its rise superposed): a [[prescribed]]",
        "# velocity_y, constant over each of 160 intervals (40 over the rise, 120 geometric to the",
        "# end), so that the line's displacement is the closed form's at every interval's end. The",
        "# top stays flat and frictionless (velocity_r free) and impermeable (a held DOF holds the",
        "# water too); Mandel's kinematics are exact, so the closed form holds in full and the lid's",
        "# reaction, /boundaries/lid/F_y, must be the force -F(t) (the run's check, where the plate",
        "# case measures the settlement instead). A surcharge ([[loads]]) would be the force without",
        "# the flat top: not Mandel's problem and without its closed form (the top would bend, its",
        "# sigma_yy held uniform instead of shifting towards the stiffer, undrained centre).",
        "#",
        "#   build/release/bin/mpile run cases/verification/mandel_lid.toml --threads 1 --out out/mandel_lid",
        "#   tools/mandel.py --compare out/mandel_lid --load-from cases/verification/mandel_plate.toml",
        'title = "Mandel\'s problem: a saturated slab under a lid moved as the closed form\'s plate"',
        'geometry = "plane_strain"',
        "",
        "[grid]",
        f"r = {toml_value(case['grid']['r'])}",
        f"y = {toml_value(case['grid']['y'])}",
        "",
        f"[materials.{soil_name}]",
    ]
    lines += [f"{k} = {toml_value(v)}" for k, v in soil.items()]
    lines += ["", "[[bodies]]"]
    lines += [f"{k} = {toml_value(v)}" for k, v in body.items()]
    lines += ["", "[[prescribed]]", 'name = "lid"', f"nodes = {{ y = {model.b!r} }}",
              f"velocity_y = {{ type = \"table\", points = [\n{rows}] }}", ""]
    lines += ["[boundaries]"] + [f"{k} = {toml_value(v)}" for k, v in case["boundaries"].items()]
    lines += ["", "[solver]"] + [f"{k} = {toml_value(v)}" for k, v in case.get("solver", {}).items()]
    for phase in case["phases"]:
        lines += ["", "[[phases]]"] + [f"{k} = {toml_value(v)}" for k, v in phase.items()]
    output = dict(case.get("output", {}))
    monitors = output.pop("monitor", [])
    lines += ["", "[output]"] + [f"{k} = {toml_value(v)}" for k, v in output.items()]
    for monitor in monitors:
        lines += ["", "[[output.monitor]]"] + [f"{k} = {toml_value(v)}" for k, v in monitor.items()]
    return "\n".join(lines) + "\n"


def describe(model, info):
    lines = [
        f"a = {model.a:g} m, b = {model.b:g} m (quarter model), F = {model.F:g} N/m on the "
        f"half-width (2F = {2 * model.F:g} N/m on the slab, sigma = F / a = {model.F / model.a:g} Pa)",
        f"G = {model.G:.6g} Pa, nu = {model.nu:g}, n = {info['porosity']:.5f}, "
        f"K_w / n = {model.M:.6g} Pa: B = {model.B:.6f}, nu_u = {model.nu_u:.6f}",
        f"k = {model.mobility * model.water_density * STANDARD_GRAVITY:.6g} m/s -> mobility "
        f"{model.mobility:.6g} m^2/(Pa s), c = {model.c:.6g} m^2/s, T = a^2 / c = {model.T:.6g} s",
        f"p0 = F B (1 + nu_u) / (3 a) = {model.p0:.6g} Pa; settlement of the plate (y = b) "
        f"undrained {model.settlement(0.0) * 1e3:.6g} mm, drained "
        f"{model.F * (1 - model.nu) * model.b / (2 * model.G * model.a) * 1e3:.6g} mm; "
        f"u_x(a) undrained {model.u_x(model.a, 0.0) * 1e3:.6g} mm, drained "
        f"{model.F * model.nu / (2 * model.G) * 1e3:.6g} mm",
    ]
    peak, tau = model.peak_centre_pressure()
    lines.append(f"Mandel-Cryer: p(0, t) peaks at {peak:.5f} p0 at c t / a^2 = {tau:.4f} "
                 f"(t = {tau * model.T:.4g} s)")
    return lines


def reference_table(model):
    print(f"{'t/T':>8} {'t (s)':>9} {'p(0)/p0':>9} {'p(a/2)/p0':>10} {'sett. (mm)':>11} "
          f"{'u_x(a) mm':>10} {'sum sigma_yy dx / F':>20}")
    x = np.linspace(0.0, model.a, 2001)
    for tau in (0.0, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0):
        t = tau * model.T
        sig = np.array([model.sigma_yy(xx, t) for xx in x])
        integral = np.sum(0.5 * (sig[1:] + sig[:-1]) * np.diff(x)) / model.F
        label = "0+" if tau == 0.0 else f"{tau:g}"
        print(f"{label:>8} {t:9.4g} {model.pressure(0.0, t) / model.p0:9.5f} "
              f"{model.pressure(0.5 * model.a, t) / model.p0:10.5f} {model.settlement(t) * 1e3:11.6f} "
              f"{model.u_x(model.a, t) * 1e3:10.6f} {integral:20.6f}")


# --- a run against it -------------------------------------------------------------------------



def _at(times, series, t):
    """The series at the first row at or after t (None past the end)."""
    k = int(np.searchsorted(times, t - 1e-12))
    return (times[k], series[k]) if k < times.size else (None, None)


def _row_times(rise, taus, period):
    """The end of the load's rise, then the times t / T = taus after it."""
    return [rise] + [tau * period for tau in taus if tau * period > rise * 1.001]


def compare(run, load_from=None):
    import h5py
    import tomllib

    mpile = mpile_package()
    path = pathlib.Path(run)
    history = path / "history.h5" if path.is_dir() else path
    case = mpile.case(history)
    has_plate = any("rigid" in body and "force_y" in body["rigid"] for body in case.get("bodies", []))
    if load_from is None and not has_plate:
        # A lid run: its force is the plate case's it was written from, the shipped one by default.
        load_from = pathlib.Path(__file__).resolve().parent.parent / DEFAULT_PLATE_CASE
        print(f"(the lid's force from {DEFAULT_PLATE_CASE}; --load-from names another)")
    load_case = None
    if load_from:
        with open(load_from, "rb") as f:
            load_case = tomllib.load(f)
    model, info = from_case(case, load_case)
    attrs = mpile.attributes(history)
    with h5py.File(history, "r", locking=False) as f:
        data = {}

        def keep(name, node):
            if isinstance(node, h5py.Dataset) and node.ndim == 1:
                data["/" + name] = node[()]
        f.visititems(keep)
        phases = {int(k): dict(v.attrs) for k, v in f["phases"].items()} if "phases" in f else {}
    solver = case.get("solver", {})
    phase_list = case["phases"]
    drive_phase = info["drive_phase"]
    index = 0 if drive_phase is None else [p["name"] for p in phase_list].index(drive_phase)
    start = float(phases.get(index, {}).get("start", 0.0))
    time = data["/time"] - start
    load = [(t, v) for t, v in info["load"]]
    rise = load[-1][0]
    plate = info["plate"]

    print(f"run: {history}")
    print(f"  {attrs.get('title', '')}; status: {attrs.get('status')}; program {attrs.get('program', '')} "
          f"commit {attrs.get('commit', '?')}; threads {attrs.get('threads')}; wall time "
          f"{float(attrs.get('wall_time', float('nan'))):.1f} s; {int(data['/step'][-1])} steps to "
          f"t = {data['/time'][-1]:.4g} s")
    overrides = [str(o.decode() if isinstance(o, bytes) else o)
                 for o in np.atleast_1d(attrs.get("overrides", []))]
    overrides = [o for o in overrides if o.strip()]
    print("  overrides: " + (" ".join(overrides) if overrides else "none"))
    print(f"  solver: implicit_pore_pressure = {solver.get('implicit_pore_pressure', False)}, "
          f"cell_mean_pore_pressure = {solver.get('cell_mean_pore_pressure', False)}, xpic_order = "
          f"{solver.get('xpic_order', 0)}, courant_number = {solver.get('courant_number', 0.8)}, "
          f"mass_scaling = {solver.get('mass_scaling', 1.0)}; dt {data['/dt'][data['/dt'] > 0].min():.3g} to "
          f"{data['/dt'].max():.3g} s")
    for line in describe(model, info):
        print("  " + line)
    print(f"  the force rises to F over {rise:g} s ({rise / model.T:.4g} T): the reference is the "
          "closed form superposed over that rise; 'step' is the ideal step load's")

    # The centre's pore pressure, compression positive, against the series at the particle's x.
    monitors = sorted({name.split("/")[2] for name in data if name.startswith("/monitors/")})
    pressure_monitors = [m for m in monitors if f"/monitors/{m}/excess_pore_pressure" in data]
    centre = min(pressure_monitors, key=lambda m: (abs(data[f"/monitors/{m}/r"][0]),
                                                   abs(data[f"/monitors/{m}/y"][0] - model.b / 2)))
    taus = [0.005, 0.01, 0.02, 0.05, 0.0833, 0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0]
    rows = [tau for tau in taus if tau * model.T <= time[-1]]
    print()
    print("pore pressure p / p0 (compression positive; monitors at their particle's x, y; the "
          "reference at the particle's x)")
    header = f"{'t/T':>7} {'t (s)':>8} {'ref.':>8} {'step':>8}"
    for m in pressure_monitors:
        header += f" {m[:14]:>14} {'err/p0':>7}"
    print(header)
    for tau in rows:
        t_want = tau * model.T
        line = None
        for m in pressure_monitors:
            tt, value = _at(time, data[f"/monitors/{m}/excess_pore_pressure"], t_want)
            if tt is None:
                continue
            x = data[f"/monitors/{m}/r"][0]
            reference = model.loaded("p", x, tt, load) / model.p0
            if line is None:
                xc = data[f"/monitors/{centre}/r"][0]
                line = (f"{tt / model.T:7.4f} {tt:8.4f} {model.loaded('p', xc, tt, load) / model.p0:8.4f} "
                        f"{model.step('p', xc, tt) / model.p0:8.4f}")
            measured = -value / model.p0
            line += f" {measured:14.4f} {measured - reference:+7.4f}"
        if line:
            print(line)
    xs = ", ".join(f"{m} ({data[f'/monitors/{m}/r'][0]:.3f}, {data[f'/monitors/{m}/y'][0]:.3f})"
                   for m in pressure_monitors)
    print(f"  (ref. and step at the first monitor's x; monitors at {xs})")

    p_centre = -data[f"/monitors/{centre}/excess_pore_pressure"] / model.p0
    x_centre = data[f"/monitors/{centre}/r"][0]
    after = time >= rise
    k = int(np.argmax(np.where(time >= 0, p_centre, -np.inf)))
    peak_ref, tau_ref = model.peak_centre_pressure()
    grid_t = time[(time > 0) & (time <= min(time[-1], 3.0 * tau_ref * model.T + rise))]
    ref_curve = np.array([model.loaded("p", x_centre, t, load) for t in grid_t]) / model.p0
    kr = int(np.argmax(ref_curve))
    print(f"centre ({centre}, x = {x_centre:.4f} m): largest p / p0 {p_centre[k]:.4f} at t = "
          f"{time[k]:.4g} s (c t / a^2 = {time[k] / model.T:.4f}); reference (the rise superposed) "
          f"{ref_curve[kr]:.4f} at {grid_t[kr] / model.T:.4f}; the step's {peak_ref:.4f} at "
          f"{tau_ref:.4f} (x = 0). Peak error {(p_centre[k] - ref_curve[kr]) / ref_curve[kr]:+.2%}; "
          f"rises above 1: {'yes' if p_centre[k] > 1.0 else 'no'}")
    summary = {"peak": float(p_centre[k]), "peak_reference": float(ref_curve[kr])}
    if np.any(after):
        ref_all = np.array([model.loaded("p", x_centre, t, load) for t in time[after]]) / model.p0
        err = p_centre[after] - ref_all
        summary["after_rise"] = float(np.max(np.abs(err)))
        print(f"  after the rise: largest |p - ref| / p0 {np.max(np.abs(err)):.4f} at t / T = "
              f"{time[after][np.argmax(np.abs(err))] / model.T:.4f}; rms {np.sqrt(np.mean(err**2)):.4f}")

    # The plate's settlement (a lid's: its prescribed motion) and the free face's u_x.
    print()
    if plate:
        u_plate = -data[f"/bodies/{plate}/u_y"]
        top = f"the plate's settlement (-u_y of {plate})"
    else:
        u_plate = np.array([-integrate_points(info["lid_velocity"], t) for t in time])
        top = f"the lid's settlement (its prescribed motion, -integral of {info['lid']}'s velocity_y)"
    faces = [m for m in monitors if f"/monitors/{m}/u_r" in data]
    face = max(faces, key=lambda m: data[f"/monitors/{m}/r"][0]) if faces else None
    header = f"{'t/T':>7} {'t (s)':>8} {'settl. mm':>10} {'ref.':>10} {'step':>10} {'rel. err':>9}"
    if face:
        x_face = data[f"/monitors/{face}/r"][0] - data[f"/monitors/{face}/u_r"][0]
        header += f" {'u_x mm':>9} {'ref.':>9} {'rel. err':>9}"
    print(f"{top} against -u_y(b, t)" +
          (f"; u_x of monitor {face} (x0 = {x_face:.4f} m) against u_x(x0, t)" if face else ""))
    print(header)
    for t_want in _row_times(rise, rows, model.T):
        tt, s = _at(time, u_plate, t_want)
        if tt is None:
            continue
        ref = -model.loaded("u_y", model.b, tt, load)
        line = (f"{tt / model.T:7.4f} {tt:8.4f} {s * 1e3:10.5f} {ref * 1e3:10.5f} "
                f"{model.settlement(tt) * 1e3:10.5f} {(s - ref) / ref:+9.2%}")
        if face:
            _, ux = _at(time, data[f"/monitors/{face}/u_r"], t_want)
            ref_x = model.loaded("u_x", x_face, tt, load)
            line += f" {ux * 1e3:9.5f} {ref_x * 1e3:9.5f} {(ux - ref_x) / ref_x:+9.2%}"
            summary["free_face"] = float(abs(ux - ref_x) / ref_x)  # the last row's: at T
        print(line)

    # The force balance.
    print()
    base = data.get("/boundaries/y_min/F_y")
    if plate:
        driving = -data[f"/bodies/{plate}/driving_F_y"]
        contact = data[f"/bodies/{plate}/contact_F_y"]
        print(f"force balance (N/m; F = {model.F:g}): the drive's force, the soil's reaction on the "
              "plate (contact_F_y), the base's support (boundaries/y_min/F_y)")
    else:
        driving = np.interp(time, [q[0] for q in load], [q[1] for q in load])
        contact = -data[f"/boundaries/{info['lid']}/F_y"]
        print(f"force balance (N/m; F = {model.F:g}): the force F(t) the lid stands for, the soil's "
              f"reaction on the lid (-boundaries/{info['lid']}/F_y), the base's support "
              "(boundaries/y_min/F_y)")
    print(f"{'t/T':>7} {'t (s)':>8} {'drive':>10} {'reaction':>10} {'err/F':>8} {'base':>10} {'err/F':>8}")
    for t_want in _row_times(rise, rows, model.T):
        tt, d = _at(time, driving, t_want)
        if tt is None:
            continue
        _, cf = _at(time, contact, t_want)
        line = f"{tt / model.T:7.4f} {tt:8.4f} {d:10.2f} {cf:10.2f} {(cf - d) / model.F:+8.2%}"
        if base is not None:
            _, bf = _at(time, base, t_want)
            line += f" {bf:10.2f} {(bf - d) / model.F:+8.2%}"
        print(line)
    if np.any(after):
        dev = (contact[after] - driving[after]) / model.F
        summary["reaction"] = float(np.max(np.abs(dev)))
        print(f"  after the rise: reaction - drive within {dev.min():+.3%} .. {dev.max():+.3%} of F, "
              f"mean {dev.mean():+.3%}")
        if base is not None:
            dev = (base[after] - driving[after]) / model.F
            print(f"  after the rise: base - drive within {dev.min():+.3%} .. {dev.max():+.3%} of F, "
                  f"mean {dev.mean():+.3%}")

    # Snapshots: the pressure profile and the section force.
    pvd = path / "particles.pvd" if path.is_dir() else path.parent / "particles.pvd"
    if pvd.exists():
        try:
            snaps = mpile.open_snapshots(pvd)
        except Exception as error:  # VTK missing: the profiles are optional
            print(f"\n(snapshots not read: {error})")
            snaps = []
        if len(snaps):
            print()
            print("snapshots: every soil particle's p against p(x, t) (cell means where "
                  "cell_mean_pore_pressure), and the force across y = b/2 against F")
            print(f"{'t/T':>7} {'t (s)':>8} {'max |dp|/p0':>12} {'rms dp/p0':>10} "
                  f"{'p(0) ref/p0':>12} {'section / F':>12} {'sigma_yy(0) err/(F/a)':>22}")
            for snap in snaps:
                tt = snap.time - start
                if tt < rise:
                    continue
                frame = snap.to_frame()
                soil_index = snap.body_names.index(info["soil"]) if snap.body_names else 0
                frame = frame[frame["body"].astype(int) == soil_index]
                x = frame["r"].to_numpy()
                measured = -frame["excess_pore_pressure"].to_numpy() / model.p0
                refs = np.array([model.loaded("p", xx, tt, load) for xx in x]) / model.p0
                dp = measured - refs
                section = snap.vertical_force([0.5 * model.b], slab=0.1 * model.b)[0] / model.F
                near = np.abs(x - x.min()) < 1e-9
                s_ref = model.loaded("sigma_yy", x.min(), tt, load)
                s_err = (frame["sigma_yy"].to_numpy()[near].mean() - s_ref) / (model.F / model.a)
                print(f"{tt / model.T:7.4f} {tt:8.4f} {np.max(np.abs(dp)):12.4f} "
                      f"{np.sqrt(np.mean(dp**2)):10.4f} {model.loaded('p', 0.0, tt, load) / model.p0:12.4f} "
                      f"{section:12.4f} {s_err:+22.4f}")

    # The energy ledger.
    print()
    terms = [n for n in ("external_work", "kinetic", "elastic", "plastic", "damping", "contact",
                         "transfer", "drag", "radiated", "residual") if f"/energy/{n}" in data]
    rel = data["/energy/relative_residual"]
    steps = data["/step"]
    late = steps > 100
    kp = int(np.argmax(np.where(late, np.abs(rel), -1)))
    print(f"energy ledger (J/m): relative residual at the end {rel[-1]:+.2%}, largest after step 100 "
          f"{rel[kp]:+.2%} at t = {time[kp]:.4g} s; status {attrs.get('status')}")
    print(f"{'t (s)':>8} " + " ".join(f"{n:>13}" for n in terms) + f" {'rel.':>8}")
    for tt in sorted({rise, 0.25 * time[-1], 0.5 * time[-1], time[kp], time[-1]}):
        k = min(int(np.searchsorted(time, tt - 1e-12)), time.size - 1)
        print(f"{time[k]:8.4f} " + " ".join(f"{data[f'/energy/{n}'][k]:13.6g}" for n in terms) +
              f" {rel[k]:+8.2%}")
    # The closed form's own ledger: the force's work on the quasi-static slab, its stored energy
    # and their difference, Darcy's dissipation.
    marks = sorted({rise, 0.1 * model.T, 0.25 * time[-1], 0.5 * time[-1], time[-1]})
    rows_k = [min(int(np.searchsorted(time, tt - 1e-12)), time.size - 1) for tt in marks]
    upto = time[(time > 0) & (time <= time[rows_k[-1]] + 1e-12)]
    work = model.work(upto, load)
    print("against the closed form's ledger (quasi-static: work = stored + Darcy's dissipation):")
    print(f"{'t (s)':>8} {'work':>9} {'ref.':>9} {'err':>7} {'elastic':>9} {'ref.':>9} {'err':>7} "
          f"{'drag':>9} {'ref.':>9} {'err':>7}")
    for k in rows_k:
        w_ref = np.interp(time[k], upto, work)
        e_ref = model.stored_energy(time[k], load)
        d_ref = w_ref - e_ref
        w, e, d = (data[f"/energy/{n}"][k] for n in ("external_work", "elastic", "drag"))
        print(f"{time[k]:8.4f} {w:9.4f} {w_ref:9.4f} {(w - w_ref) / w_ref:+7.2%} {e:9.4f} {e_ref:9.4f} "
              f"{(e - e_ref) / e_ref:+7.2%} {d:9.4f} {d_ref:9.4f} {(d - d_ref) / d_ref:+7.2%}")
    status = str(attrs.get("status", ""))
    print("stopped by a guard: " + ("yes: " + status if ("unstable" in status or "failed" in status)
                                     else "no"))
    summary["residual_peak"] = float(abs(rel[kp]))
    summary["complete"] = status.startswith("complete")
    return summary


def check(summary, expect):
    """The run's summary against the bounds asked for (--expect NAME=BOUND): the peak's relative
    error, the largest |p - ref| / p0 after the rise, |reaction - drive| / F after the rise, the
    largest relative energy residual after step 100, and the free face's u_x at T, relative.
    Returns the failures."""
    failures = [] if summary["complete"] else ["the run did not complete"]
    measured = {"peak": abs(summary["peak"] - summary["peak_reference"]) / summary["peak_reference"],
                "after_rise": summary.get("after_rise", float("inf")),
                "reaction": summary.get("reaction", float("inf")),
                "residual": summary["residual_peak"],
                "free_face": summary.get("free_face", float("inf"))}
    for name, bound in expect.items():
        if not measured[name] <= bound:
            failures.append(f"{name} {measured[name]:.4g} > {bound:g}")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--case", help="a Mandel case file: print its closed form at a few times")
    what.add_argument("--compare", metavar="RUN_DIR", help="a run's directory (or its history.h5)")
    what.add_argument("--write-lid", nargs=2, metavar=("PLATE_CASE", "LID_CASE"),
                      help="write the lid variant of a plate case (the top moved as the closed "
                           "form's plate)")
    parser.add_argument("--expect", action="append", default=[], metavar="NAME=BOUND",
                        help="with --compare: fail (exit 1) unless NAME (peak: the centre's peak "
                             "p's relative error; after_rise: max |p - ref| / p0 after the rise; "
                             "reaction: max |reaction - drive| / F after it; residual: the largest "
                             "relative energy residual after step 100; free_face: the free face's "
                             "u_x at T, relative) is at most BOUND")
    parser.add_argument("--load-from", metavar="PLATE_CASE",
                        help="with --compare on a lid run: the plate case whose force it stands for "
                             f"(default {DEFAULT_PLATE_CASE})")
    args = parser.parse_args()
    if args.write_lid:
        pathlib.Path(args.write_lid[1]).write_text(lid_case_text(args.write_lid[0]))
        print(args.write_lid[1])
        return
    if args.case:
        import tomllib
        with open(args.case, "rb") as f:
            case = tomllib.load(f)
        if "base" in case:
            sys.exit(f"{args.case}: a case with a base is read through a run (--compare)")
        load_case = None
        if not any("rigid" in body and "force_y" in body["rigid"] for body in case.get("bodies", [])):
            load_from = args.load_from or (pathlib.Path(__file__).resolve().parent.parent /
                                           DEFAULT_PLATE_CASE)
            with open(load_from, "rb") as f:
                load_case = tomllib.load(f)
        model, info = from_case(case, load_case)
        for line in describe(model, info):
            print(line)
        print()
        reference_table(model)
    else:
        summary = compare(args.compare, args.load_from)
        if args.expect:
            names = ("peak", "after_rise", "reaction", "residual", "free_face")
            sys.exit(expect_check("mandel", args.expect, names, check, summary))


if __name__ == "__main__":
    main()
