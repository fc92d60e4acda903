#!/usr/bin/python3
"""An independent reference for the Hertz impact (cases/verification/hertz_sphere.toml): the same
elastic sphere dropped on a rigid plane, by small-strain axisymmetric finite elements, in a few
hundred lines that share nothing with the engine (docs/verification.md, "Contact timing").

  tools/hertz_fe.py --velocity 0.1 --cell 1e-3        # R = 0.1 m, E = 1 MPa, nu = 0.3, 1000 kg/m^3
  tools/hertz_fe.py --cell 1e-3 --quasi-static        # no inertia in the sphere's deformation

Hertz's contact time treats the sphere near the contact as a half-space, its deformation
quasi-static; the sphere here is finite (its patch reaches 0.13 R) and rings with a period a
quarter of the contact's. By default this solves the elastodynamics of the whole sphere: 4-node
axisymmetric elements (2 x 2 Gauss points) on a square grid of cell size h clipped to the sphere,
the nodes of its outer layer moved radially onto the circle; lumped masses; central differences at
0.9 of the stable step (the largest eigenvalue of M^-1 K by power iteration); the plane a kinematic
constraint on each node (a node that would pass it is put on it, frictionless, and leaves it when
its velocity does). It prints the contact time and the peak force against Hertz's and the
energy's balance.

--quasi-static keeps the same finite sphere and elements but takes the inertia out of the
deformation: the sphere decelerates as a rigid body, deformed statically by the plane's pressure
and the uniform d'Alembert body force F/M per unit mass that balances it. The global stiffness
(u_r = 0 on the axis), condensed onto the outer layer's lowest nodes, gives at a sequence of
approaches delta of the centre of mass the frictionless unilateral contact by an active set (a
node that would pass the plane held on it, one whose reaction pulls released) and so F(delta);
then t_c = 2 int_0^delta_max d delta / sqrt(v^2 - (2/M) int_0^delta F), delta_max where the root
vanishes. It prints F against Hertz's 4/3 E* R^(1/2) delta^(3/2) (per 2 pi: per radian), the
contact time, delta_max and the peak force against Hertz's. Against Hertz's time this mode
measures the finite sphere; the default, against this mode, measures the dynamics.
"""
import argparse

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

RADIUS, YOUNG, POISSON, DENSITY = 0.1, 1e6, 0.3, 1000.0


def mesh(h):
    """Nodes and 4-node elements of the half disk r >= 0 of the sphere centred at (0, R)."""
    cells_r, cells_y = int(round(RADIUS / h)), int(round(2 * RADIUS / h))
    number = -np.ones((cells_y + 1, cells_r + 1), dtype=int)
    coords, elements = [], []
    for j in range(cells_y):
        for i in range(cells_r):
            if ((i + 0.5) * h) ** 2 + ((j + 0.5) * h - RADIUS) ** 2 >= RADIUS**2:
                continue
            corners = []
            for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                if number[b, a] < 0:
                    number[b, a] = len(coords)
                    coords.append((a * h, b * h))
                corners.append(number[b, a])
            elements.append(corners)
    x = np.array(coords)
    elements = np.array(elements)
    # The outer layer (nodes in fewer elements than inside: 4, or 2 on the axis) onto the circle.
    count = np.bincount(elements.ravel(), minlength=len(x))
    outer = np.where(x[:, 0] == 0.0, count < 2, count < 4)
    scale = np.ones(len(x))
    scale[outer] = RADIUS / np.hypot(x[outer, 0], x[outer, 1] - RADIUS)
    x[:, 0] *= scale
    x[:, 1] = RADIUS + (x[:, 1] - RADIUS) * scale
    return x, elements


def stiffness_and_mass(x, elements):
    """Each element's 8 x 8 stiffness per radian (strains r, y, theta, ry) and the lumped masses."""
    lam = YOUNG * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
    mu = YOUNG / (2 * (1 + POISSON))
    d = np.array([[lam + 2 * mu, lam, lam, 0], [lam, lam + 2 * mu, lam, 0],
                  [lam, lam, lam + 2 * mu, 0], [0, 0, 0, mu]])
    g = 1 / np.sqrt(3)
    k = np.zeros((len(elements), 8, 8))
    m = np.zeros(len(x))
    xe = x[elements]
    for xi, eta in ((-g, -g), (g, -g), (g, g), (-g, g)):
        n = 0.25 * np.array([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta),
                             (1 - xi) * (1 + eta)])
        dn = 0.25 * np.array([[-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)],
                              [-(1 - xi), -(1 + xi), 1 + xi, 1 - xi]])
        jac = np.einsum("ak,ekb->eab", dn, xe)
        det = jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0]
        inverse = np.stack([np.stack([jac[:, 1, 1], -jac[:, 0, 1]], 1),
                            np.stack([-jac[:, 1, 0], jac[:, 0, 0]], 1)], 1) / det[:, None, None]
        dndx = np.einsum("eba,bk->eak", inverse, dn)
        r = xe[:, :, 0] @ n
        b = np.zeros((len(elements), 4, 8))
        b[:, 0, 0::2] = dndx[:, 0]
        b[:, 1, 1::2] = dndx[:, 1]
        b[:, 2, 0::2] = n[None, :] / r[:, None]
        b[:, 3, 0::2] = dndx[:, 1]
        b[:, 3, 1::2] = dndx[:, 0]
        weight = r * det
        k += np.einsum("eia,ij,ejb,e->eab", b, d, b, weight)
        np.add.at(m, elements, (DENSITY * weight)[:, None] * n[None, :])
    return k, m


def hertz(velocity):
    """Hertz's maximum approach, contact time and F(delta) per radian for this sphere."""
    e_star = YOUNG / (1 - POISSON**2)
    sphere = 4 / 3 * np.pi * RADIUS**3 * DENSITY
    delta = (15 * sphere * velocity**2 / (16 * e_star * np.sqrt(RADIUS))) ** 0.4
    return (delta, 2.9432751 * delta / velocity,
            lambda d: 4 / 3 * e_star * np.sqrt(RADIUS) * d**1.5 / (2 * np.pi))


def contact_time(delta, force, mass, velocity):
    """2 * integral of d delta / sqrt(v^2 - (2/M) W(delta)) to where the root vanishes, W the
    integral of F, for F given at ascending approaches delta from 0 and linear between them; returns
    the time and delta_max. delta = delta_max (1 - tau^2) takes the root's zero out of the
    integrand."""
    work = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(delta))])
    stop = 0.5 * mass * velocity**2
    i = np.searchsorted(work, stop) - 1  # W reaches the kinetic energy in [delta_i, delta_i+1]
    if i + 1 >= len(delta):
        raise ValueError("the approaches end before the sphere stops")

    def energy(d):  # W, quadratic in each interval
        j = np.clip(np.searchsorted(delta, d) - 1, 0, len(delta) - 2)
        s = d - delta[j]
        slope = (force[j + 1] - force[j]) / (delta[j + 1] - delta[j])
        return work[j] + force[j] * s + 0.5 * slope * s * s

    slope = (force[i + 1] - force[i]) / (delta[i + 1] - delta[i])
    rest = stop - work[i]  # = F_i s + slope s^2 / 2
    delta_max = delta[i] + 2 * rest / (force[i] + np.sqrt(force[i] ** 2 + 2 * slope * rest))
    tau = (np.arange(20000) + 0.5) / 20000
    speed = np.sqrt(np.maximum(velocity**2 - 2 * energy(delta_max * (1 - tau * tau)) / mass, 0.0))
    return 2 * np.mean(2 * delta_max * tau / speed), delta_max


def quasi_static(x, elements, k, m, velocity, steps):
    """F(delta) of the sphere under the plane's frictionless unilateral contact and the uniform
    d'Alembert body force -F/M per unit mass that balances it, delta the approach of its centre of
    mass, from the global stiffness; then the contact time of its rigid-body deceleration."""
    dofs = np.stack([2 * elements, 2 * elements + 1], axis=2).reshape(len(elements), 8)
    n = 2 * len(x)
    rows, columns = np.repeat(dofs, 8, axis=1).ravel(), np.tile(dofs, (1, 8)).ravel()
    stiffness = scipy.sparse.coo_matrix((k.ravel(), (rows, columns)), shape=(n, n)).tocsr()
    free = np.setdiff1d(np.arange(n), 2 * np.nonzero(x[:, 0] == 0.0)[0])  # u_r = 0 on the axis
    weight = np.zeros(n)
    weight[1::2] = m
    # [K m_y; m_y^T 0] [w; mu] = [p; 0]: w the deformation under p and the body force -mu m_y that
    # balances it (mu = sum(p) / M), with the centre of mass fixed.
    bordered = scipy.sparse.bmat([[stiffness[free][:, free], weight[free][:, None]],
                                  [weight[free][None, :], None]], format="csc")
    solve = scipy.sparse.linalg.splu(bordered).solve
    height = x[:, 1] - x[:, 1].min()
    count = np.bincount(elements.ravel(), minlength=len(x))
    outer = np.where(x[:, 0] == 0.0, count < 2, count < 4)
    delta_hertz, _, _ = hertz(velocity)
    # Only the outer layer's nodes can touch first (the others lie inside the circle).
    candidates = np.nonzero(outer & (height < 3 * delta_hertz))[0]
    where = np.searchsorted(free, 2 * candidates + 1)
    load = np.zeros((len(free) + 1, len(candidates)))
    load[where, np.arange(len(candidates))] = 1.0
    flexibility = solve(load)[where]  # G: y displacement at candidate i from a unit force up at j
    flexibility = 0.5 * (flexibility + flexibility.T)
    h = height[candidates]
    approaches = delta_hertz * np.arange(steps + 1) / (0.7 * steps)  # to 1.43 delta_Hertz
    forces = np.zeros_like(approaches)
    patch = np.zeros_like(approaches)  # the radius of the outermost node on the plane
    active = np.array([np.argmin(h)])
    tolerance = 1e-12 * RADIUS
    for s, delta in enumerate(approaches[1:], 1):
        for _ in range(200):  # from the last approach's set
            reaction = np.linalg.solve(flexibility[np.ix_(active, active)], delta - h[active])
            if (reaction < 0.0).any():  # released: pulls
                active = active[reaction >= 0.0]
                continue
            gap = h + flexibility[:, active] @ reaction - delta
            gap[active] = 0.0
            if (gap < -tolerance).any():  # would pass the plane: held on it
                active = np.union1d(active, np.nonzero(gap < -tolerance)[0])
                continue
            break
        else:
            raise RuntimeError("the active set did not settle")
        forces[s] = reaction.sum()
        patch[s] = x[candidates[active], 0].max()
    time, delta_max = contact_time(approaches, forces, m.sum(), velocity)
    # At the deepest approach no node at all, not only the candidates, may pass the plane.
    load = np.zeros(len(free) + 1)
    load[where[active]] = reaction
    deformation = np.zeros(n)
    deformation[free] = solve(load)[:-1]
    least_gap = (height + deformation[1::2] - approaches[-1]).min()  # 0 on the nodes held
    return approaches, forces, patch, time, delta_max, least_gap, candidates


def report_quasi_static(x, elements, k, m, args):
    delta_hertz, hertz_time, hertz_force = hertz(args.velocity)
    approaches, forces, patch, time, delta_max, least_gap, candidates = quasi_static(
        x, elements, k, m, args.velocity, args.steps)
    # The same integral on Hertz's F(delta) and the sphere's mass checks it (2.9433 delta_max / v).
    sphere = 4 / 3 * np.pi * RADIUS**3 * DENSITY / (2 * np.pi)
    check, _ = contact_time(approaches, hertz_force(approaches), sphere, args.velocity)
    passes = ("no node passes the plane" if least_gap > -1e-9 * RADIUS
              else f"a node passes the plane by {-least_gap:.3e} m")
    print(f"h = {args.cell:g} m, {len(elements)} elements, quasi-static, mass {m.sum():.5f} "
          f"kg/rad; {len(candidates)} nodes may touch; {passes} at "
          f"{approaches[-1] / delta_hertz:.2f} Hertz's delta_max")
    shallow = np.array([0.05, 0.1, 0.2, 0.5, 1.0]) * delta_hertz
    ratios = np.interp(shallow, approaches, forces) / hertz_force(shallow)
    ratios = [f"{d / delta_hertz:g} {ratio:.4f}" for d, ratio in zip(shallow, ratios)]
    print("F / Hertz's at delta / Hertz's delta_max = " + ", ".join(ratios))
    print(f"the integral on Hertz's F(delta): {1e3 * check:.4f} ms against {1e3 * hertz_time:.4f}")
    peak, hertz_peak = np.interp(delta_max, approaches, forces), hertz_force(delta_hertz)
    widest = patch[np.searchsorted(approaches, delta_max) - 1]
    print(f"contact time {1e3 * time:.3f} ms against Hertz's {1e3 * hertz_time:.3f} "
          f"({100 * (time / hertz_time - 1):+.2f} %); delta_max {1e3 * delta_max:.4f} mm against "
          f"{1e3 * delta_hertz:.4f} ({100 * (delta_max / delta_hertz - 1):+.2f} %); peak force "
          f"{peak:.4f} N/rad against {hertz_peak:.4f} ({100 * (peak / hertz_peak - 1):+.2f} %); "
          f"patch to r = {1e3 * widest:.1f} mm (sqrt(R delta_max) "
          f"{1e3 * np.sqrt(RADIUS * delta_max):.1f})")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--velocity", type=float, default=0.1, help="impact velocity (m/s)")
    parser.add_argument("--cell", type=float, default=1e-3, help="element size h (m)")
    parser.add_argument("--quasi-static", action="store_true",
                        help="the same sphere without inertia in its deformation (above)")
    parser.add_argument("--steps", type=int, default=2000,
                        help="quasi-static: approaches, 0.7 of them to Hertz's delta_max (2000)")
    args = parser.parse_args()
    x, elements = mesh(args.cell)
    k, m = stiffness_and_mass(x, elements)
    if args.quasi_static:
        report_quasi_static(x, elements, k, m, args)
        return
    dofs = np.stack([2 * elements, 2 * elements + 1], axis=2).reshape(len(elements), 8)
    mass = np.repeat(m, 2)
    axis = 2 * np.nonzero(x[:, 0] == 0.0)[0]

    def force(u):
        out = np.zeros_like(u)
        np.add.at(out, dofs.ravel(), np.einsum("eab,eb->ea", k, u[dofs]).ravel())
        return out

    trial = np.random.default_rng(1).standard_normal(2 * len(x))
    for _ in range(300):
        image = force(trial) / mass
        image[axis] = 0.0
        largest = np.linalg.norm(image) / np.linalg.norm(trial)
        trial = image / np.linalg.norm(image)
    dt = 0.9 * 2.0 / np.sqrt(largest)

    height = x[:, 1] - x[:, 1].min()  # the lowest node on the plane at t = 0
    u = np.zeros(2 * len(x))
    v = np.zeros(2 * len(x))
    v[1::2] = -args.velocity
    initial = 0.5 * np.sum(mass * v * v)
    internal = force(u)
    t, touch, release, peak, least = 0.0, None, None, 0.0, 1.0
    while t < 0.2 and not (release is not None and t > release + 0.005):
        v_new = v - dt * internal / mass
        v_new[axis] = 0.0
        gap = height + u[1::2]
        through = gap + dt * v_new[1::2] < 0.0
        contact = 0.0
        if through.any():
            held = np.where(through, -gap / dt, v_new[1::2])
            contact = np.sum(m * (held - v_new[1::2])) / dt  # N/rad, up on the sphere
            v_new[1::2] = held
        v = v_new
        u += dt * v
        t += dt
        internal = force(u)
        if contact > 0.0:
            touch = t - dt if touch is None else touch
            release = t
            peak = max(peak, contact)
        least = min(least, (0.5 * np.sum(mass * v * v) + 0.5 * u @ internal) / initial)

    e_star = YOUNG / (1 - POISSON**2)
    sphere = 4 / 3 * np.pi * RADIUS**3 * DENSITY
    delta = (15 * sphere * args.velocity**2 / (16 * e_star * np.sqrt(RADIUS))) ** 0.4
    hertz_time = 2.9432751 * delta / args.velocity
    hertz_force = 4 / 3 * e_star * np.sqrt(RADIUS) * delta**1.5 / (2 * np.pi)
    duration = release - touch
    print(f"h = {args.cell:g} m, {len(elements)} elements, step {dt:.3e} s, mass {m.sum():.5f} kg/rad "
          f"(sphere {sphere / (2 * np.pi):.5f})")
    print(f"contact time {1e3 * duration:.3f} ms against Hertz's {1e3 * hertz_time:.3f} "
          f"({100 * (duration / hertz_time - 1):+.2f} %); peak force {peak:.4f} N/rad against "
          f"{hertz_force:.4f} ({100 * (peak / hertz_force - 1):+.2f} %); kinetic energy back "
          f"{0.5 * np.sum(mass * v * v) / initial:.4f}, kinetic + elastic at least {least:.4f}")


if __name__ == "__main__":
    main()
