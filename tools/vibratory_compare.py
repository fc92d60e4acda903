#!/usr/bin/python3
"""Vogelsang's vibratory model test (docs/vibratory-model-test.md): a run's penetration after the
start of vibration against the measured one, and the pore pressure at the monitor nearest PPT A.

    tools/vibratory_compare.py /tmp/vib_runs/run2            # a run's directory or its history.h5
    tools/vibratory_compare.py RUN --phase vibration --ppt-a 0.035 0.62
    tools/vibratory_compare.py --resolution out/vib_hg:1 --resolution out/vib_fine:0.5 \
        --resolution out/vib_finer:0.3333333333333333     # H: the cell, in pile radii

Penetration is the rigid body's /bodies/<body>/penetration less its value where the vibration phase
starts (the jacking or settlement before it is not counted, as [S24] subtracts its pile's
settlement under its own weight), averaged over one cycle centred on each time, as the page's
section 3 reads [S24]'s simulated curves; the measured column is the experiment's mean trend. A
window that would reach past the run's last row is moved back to end there, and its centre is
printed. The cycle is 1 / the drive's frequency (the phase's harmonic force_y, or --frequency).

The pore pressure is the monitor's pore_pressure (relative to the atmosphere with a [water] level,
tension positive in the file, printed compression positive, kPa), its least and greatest value in
each 0.5 s of vibration against [S24] Fig. 3's. The monitor is the one whose particle started
nearest PPT A's assumed position (--ppt-a; the page: beside the pile, 0.19 m deep, radius not
given). A monitor follows its particle, the transducer stays put: the columns compare a point
of the soil with a point in space.

What carries the tip: for each 0.5 s window, the penetration's rate (mm a cycle), the soil's mean
upward force on the tip (/reactions/<body>/tip/F_y, N/rad) and the share of it the pore pressure
carries (pore_F_y over F_y), where the history records them: a pile whose tip stands on water
rather than on the grains sinks less a cycle.

With --tip-zone R, from the run's particle snapshots: the sand within R (the pile's radius) of the
axis and within R below the tip (the rigid body's lowest particle), its mean void ratio, mean
effective pressure p' and mean excess pore pressure, at each snapshot of the vibration: whether
the grains under the tip still carry it.

With --resolution RUN:H for each of three or more runs of one case at cell sizes H, the penetration
at each measured time is extrapolated to a vanishing cell by tools/convergence.py's rules: the
observed order p of the three finest (f = f0 + C H^p, p in [0.5, 4]), Richardson on the two finest
and Roache's band 1.25 |f1 - f2| / ((H2 / H1)^p - 1). Where the three oscillate or their
differences do not shrink as H^p, the row says so and gives no extrapolation.
"""
import argparse
import math
import pathlib
import sys
import tomllib

import h5py
import numpy as np

import convergence

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "python"))

# Staubach P (2024) Hydro-mechanically coupled CEL analyses with effective contact stresses,
# Int. J. Numer. Anal. Methods Geomech., doi:10.1002/nag.3725 ([S24]), Fig. 2, read to 0.1 mm in
# docs/vibratory-model-test.md section 3: penetration after the start of vibration (mm, downward
# positive); the experiment's mean trend and the CEL run with mu = 0.25 on the effective normal
# stress (averaged over one cycle centred on t).
TIMES = (0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75, 3.0)
MEASURED_MM = {0.25: 7.8, 0.5: 21.4, 0.75: 39.9, 1.0: 59.0, 1.5: 93.3, 2.0: 122.7, 2.5: 149.5,
               3.0: 174.5}
CEL_MM = {0.25: 15.3, 0.5: 32.8, 0.75: 52.3, 1.0: 67.4, 1.5: 94.5, 2.0: 120.8, 2.5: 145.5,
          3.0: 168.5}

# [S24] Fig. 3: the pore pressure at PPT A, least / greatest in each 0.5 s (kPa), measured and the
# CEL run with mu = 0.25 (docs/vibratory-model-test.md section 3).
PPT_WINDOWS = ((0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (1.5, 2.0), (2.0, 2.5), (2.5, 3.0))
PPT_MEASURED_KPA = ((1.6, 4.8), (1.3, 5.2), (1.6, 5.0), (2.0, 4.4), (2.1, 4.2), (2.2, 4.0))
PPT_CEL_KPA = ((1.2, 4.8), (0.9, 5.4), (1.4, 4.2), (2.1, 4.0), (2.3, 3.9), (2.0, 3.7))

# PPT A's position in the axisymmetric model (r, y), m: ASSUMED. Depth 0.19 m below the surface
# (the tip's depth when the pile passes it at about 0.8 s: 0.15 + 0.044 m, the page's section 1)
# under the chamber's 0.81 m surface; the radius is not given (35 mm, 2.1 pile radii).
PPT_A = (0.035, 0.81 - 0.19)


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def cycle_mean(time, values, centre, period):
    """The mean of a row series over [centre - period / 2, centre + period / 2], the trapezoid rule
    on the rows inside with the window's ends interpolated; moved back to end at the last row when
    it would pass it. Returns (mean, the window's centre)."""
    time = np.asarray(time, float)
    values = np.asarray(values, float)
    start, end = centre - 0.5 * period, centre + 0.5 * period
    if end > time[-1]:
        start, end = time[-1] - period, time[-1]
    if start < time[0]:
        raise ValueError(f"a cycle about t = {centre:g} s reaches before the first row")
    inside = (time > start) & (time < end)
    t = np.concatenate(([start], time[inside], [end]))
    v = np.concatenate(([np.interp(start, time, values)], values[inside],
                        [np.interp(end, time, values)]))
    return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)) / (end - start)), 0.5 * (start + end)


def drive_frequency(case, phase_name):
    """The frequency of the phase's harmonic force_y, or None."""
    for phase in case.get("phases", []):
        if phase.get("name") == phase_name:
            force = phase.get("drive", {}).get("force_y")
            if isinstance(force, dict) and force.get("type") == "harmonic":
                return float(force["frequency"])
    return None


def read_run(path, phase_name, body=None):
    """What the comparison needs from history.h5: the case, its attributes, time since the phase's
    start, the body's penetration since then, and each monitor's first position and pore pressure."""
    path = pathlib.Path(path)
    history = path / "history.h5" if path.is_dir() else path
    with h5py.File(history, "r", locking=False) as f:
        attrs = {k: f.attrs[k] for k in f.attrs}
        resolved = attrs.get("case_resolved") or attrs.get("case_text")
        case = tomllib.loads(text(resolved)) if resolved is not None else {}
        phases = {text(g.attrs["name"]): dict(g.attrs) for g in f["phases"].values()}
        if phase_name not in phases:
            raise SystemExit(f"{history}: no phase named {phase_name!r} (phases: "
                             f"{', '.join(phases)})")
        start = float(phases[phase_name]["start"])
        bodies = sorted(f["bodies"].keys()) if "bodies" in f else []
        if body is None:
            if len(bodies) != 1:
                raise SystemExit(f"{history}: name the body (--body), one of {bodies}")
            body = bodies[0]
        time = f["time"][()]
        penetration = f[f"bodies/{body}/penetration"][()]
        tip = f.get(f"reactions/{body}/tip")
        tip_forces = ((tip["F_y"][()], tip["pore_F_y"][()])
                      if tip is not None and "F_y" in tip and "pore_F_y" in tip else None)
        monitors = {}
        for name, group in (f["monitors"].items() if "monitors" in f else []):
            if "pore_pressure" not in group:
                continue
            r, y = group["r"][()], group["y"][()]
            first = np.flatnonzero(np.isfinite(r) & np.isfinite(y))
            if first.size:
                monitors[name] = ((float(r[first[0]]), float(y[first[0]])), group["pore_pressure"][()])
    keep = time >= start
    if not np.any(keep):
        raise SystemExit(f"{history}: the run has not reached phase {phase_name!r}")
    start_penetration = float(np.interp(start, time, penetration))
    return {"history": history, "attrs": attrs, "case": case, "body": body, "start": start,
            "time": time[keep] - start, "penetration": penetration[keep] - start_penetration,
            "start_penetration": start_penetration,
            "monitors": {n: (pos, p[keep]) for n, (pos, p) in monitors.items()},
            "tip": None if tip_forces is None else tuple(values[keep] for values in tip_forces)}


def penetration_rows(run, period):
    """(t, cycles, computed mm or None, window centre) for each of TIMES the run covers."""
    time, pen = run["time"], run["penetration"]
    rows = []
    for t in TIMES:
        if t + 0.5 * period > time[-1] + period:  # not reached: more than half a cycle short
            rows.append((t, t / period, None, None))
            continue
        mean, centre = cycle_mean(time, pen, t, period)
        rows.append((t, t / period, 1e3 * mean, centre))
    return rows


def nearest_monitor(monitors, point):
    if not monitors:
        return None
    return min(monitors, key=lambda n: math.dist(monitors[n][0], point))


def pore_rows(time, pore):
    """(window, least, greatest, mean) of the pore pressure, compression positive, kPa, per window;
    the mean by the trapezoid rule over the rows inside (they need not be evenly spaced: a phase's
    end adds one)."""
    rows = []
    for a, b in PPT_WINDOWS:
        inside = (time >= a) & (time <= b) & np.isfinite(pore)
        if b > time[-1] + 1e-9 or np.count_nonzero(inside) < 2:
            rows.append(((a, b), None, None, None))
            continue
        t, u = time[inside], -pore[inside] / 1e3
        mean = float(np.sum(0.5 * (u[1:] + u[:-1]) * np.diff(t)) / (t[-1] - t[0]))
        rows.append(((a, b), float(u.min()), float(u.max()), mean))
    return rows


def window_mean(time, values, a, b):
    """The mean of the piecewise linear `values` over [a, b] exactly: the rows inside and the values
    interpolated at both ends (a row written a rounding off a window's end is not lost)."""
    t = np.concatenate(([a], time[(time > a) & (time < b)], [b]))
    v = np.interp(t, time, values)
    return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)) / (b - a))


def tip_rows(run, period):
    """(window, mm a cycle, mean tip F_y in N/rad, the pore pressure's share of it) per 0.5 s window
    the run covers, the means by the trapezoid rule; None for the forces without a tip record."""
    time, pen = run["time"], run["penetration"]
    rows = []
    for a, b in PPT_WINDOWS:
        if b > time[-1] + 1e-9:
            continue
        rate = 1e3 * (np.interp(b, time, pen) - np.interp(a, time, pen)) / (b - a) * period
        total = pore = None
        if run["tip"] is not None:
            total, pore = (window_mean(time, values, a, b) for values in run["tip"])
        rows.append(((a, b), rate, total, None if total is None or total == 0.0 else pore / total))
    return rows


def tip_zone(snapshot, radius, axisymmetric=True):
    """(tip's height, particles, their volumes' sum over the zone's, mean void ratio, mean p' in kPa,
    mean excess pore pressure in kPa, compression positive) of the sand within `radius` of the
    axis and `radius` below the tip in a saturated run's snapshot (positions; arrays material,
    volume, void_ratio, p, pore_pressure, excess_pore_pressure; material_names, rigid bodies'
    ending in "(rigid)"); all but the first two None without such sand. The zone's volume is
    radius^3 / 2 per radian (axisymmetric), else radius^2 per unit thickness: particles that keep
    their volumes and positions consistent fill it about once; crowded particles, more than once."""
    from mpile.snapshots import rigid_particles

    rigid = rigid_particles(snapshot)
    r, y = snapshot.positions[:, 0], snapshot.positions[:, 1]
    tip = float(y[rigid].min())
    zone = ~rigid & (r < radius) & (y < tip) & (y > tip - radius)
    if not zone.any():
        return tip, 0, None, None, None, None
    a = snapshot.arrays
    # A saturated particle's stress is total and p its mean pressure, compression positive; the pore
    # pressures are written tension positive (physics.md section 9), so p' = p + pore_pressure.
    effective = a["p"][zone] + a["pore_pressure"][zone]
    filled = float(a["volume"][zone].sum()) / (0.5 * radius**3 if axisymmetric else radius**2)
    return (tip, int(zone.sum()), filled, float(a["void_ratio"][zone].mean()), float(effective.mean()) / 1e3,
            float(-a["excess_pore_pressure"][zone].mean()) / 1e3)


def print_tip_zone(run, radius):
    from mpile.snapshots import open_snapshots

    print()
    print(f"the sand within {1e3 * radius:g} mm of the axis and below the tip (snapshots):")
    print()
    print("| t (s) | tip y (m) | particles | their volume / the zone's | void ratio | p' (kPa) | "
          "excess pore pressure (kPa) |")
    print("|---|---|---|---|---|---|---|")
    axisymmetric = str(run["case"].get("geometry", "axisymmetric")) == "axisymmetric"
    for snapshot in open_snapshots(pathlib.Path(run["history"]).parent):
        t = snapshot.time - run["start"]
        if t < -1e-9:
            continue
        tip, count, filled, e, p, u = tip_zone(snapshot, radius, axisymmetric)
        print(f"| {t:.2f} | {tip:.4f} | {count} | {fmt(filled, 2)} | {fmt(e, 3)} | {fmt(p)} | {fmt(u)} |")


def fmt(value, digits=1):
    return "-" if value is None else f"{value:.{digits}f}"


def resolution_rows(runs, period):
    """For (h, run) pairs: (t, [mm per run, finest first], (f0, band, p) or a reason) for each
    measured time all the runs reach."""
    runs = sorted(runs, key=lambda pair: pair[0])
    h = [pair[0] for pair in runs]
    columns = [penetration_rows(run, period) for _, run in runs]
    rows = []
    for i, t in enumerate(TIMES):
        f = [column[i][2] for column in columns]
        if any(value is None for value in f):
            continue
        f0, band, p, observed = convergence.extrapolate(h, f, 1.0)
        if observed:
            rows.append((t, f, (f0, band, p)))
        elif convergence.oscillates(f[:3]):
            rows.append((t, f, "oscillates"))
        else:  # extrapolate's fallback order is an assumption: none is printed
            rows.append((t, f, "no order: the differences do not shrink as h^p"))
    return h, rows


def print_resolutions(specs, phase, body, frequency):
    runs = []
    for spec in specs:
        path, _, h = spec.rpartition(":")
        try:
            size = float(h)
        except ValueError:
            size = float("nan")
        if not path or not size > 0.0 or not math.isfinite(size):
            raise SystemExit(f"--resolution {spec}: give RUN:H, H the cell in pile radii (a "
                             f"positive number)")
        runs.append((size, read_run(path, phase, body)))
    if len(runs) < 3:
        raise SystemExit("--resolution: three runs or more (an order is observed from three)")
    period = 1.0 / (frequency or drive_frequency(runs[0][1]["case"], phase))
    h, rows = resolution_rows(runs, period)
    print("| t (s) | " + " | ".join(f"h = {value:.3g}" for value in h) +
          " | observed order | extrapolated (mm) | measured | CEL mu = 0.25 |")
    print("|---|" + "---|" * len(h) + "---|---|---|---|")
    for t, f, result in rows:
        if isinstance(result, str):
            order, value = result, "-"
        else:
            order, value = f"{result[2]:.2f}", f"{result[0]:.1f} +- {result[1]:.1f}"
        print(f"| {t:.2f} | " + " | ".join(fmt(v) for v in f) +
              f" | {order} | {value} | {fmt(MEASURED_MM.get(t))} | {fmt(CEL_MM.get(t))} |")
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", nargs="?", help="the run's output directory or its history.h5")
    parser.add_argument("--resolution", action="append", default=[], metavar="RUN:H",
                        help="instead of one run: three or more of one case at cell size H (pile "
                             "radii), extrapolated to a vanishing cell")
    parser.add_argument("--phase", default="vibration", help="the vibration phase (default vibration)")
    parser.add_argument("--body", help="the pile (default: the only rigid body)")
    parser.add_argument("--frequency", type=float,
                        help="the cycle's frequency, Hz (default: the phase's harmonic force_y)")
    parser.add_argument("--ppt-a", type=float, nargs=2, default=PPT_A, metavar=("R", "Y"),
                        help=f"PPT A's position, m (default {PPT_A[0]:g} {PPT_A[1]:g}, assumed)")
    parser.add_argument("--tip-zone", type=float, metavar="R",
                        help="also the sand within R (m, the pile's radius) of the axis below the tip, "
                             "from the snapshots")
    parser.add_argument("--expect", action="append", default=[], metavar="T=BAND",
                        help="fail (exit 1) unless the penetration at T s (one of the measured "
                             "times) is within BAND of the measured one, |computed / measured - 1| "
                             "<= BAND; prints 'vibratory check: ok' or the failures")
    args = parser.parse_args(argv)
    if args.resolution:
        if args.run or args.expect:
            parser.error("--resolution compares runs: no run and no --expect beside it")
        return print_resolutions(args.resolution, args.phase, args.body, args.frequency)
    if not args.run:
        parser.error("give a run (or --resolution runs)")

    run = read_run(args.run, args.phase, args.body)
    frequency = args.frequency or drive_frequency(run["case"], args.phase)
    if not frequency:
        raise SystemExit("the phase drives no harmonic force_y: give --frequency")
    period = 1.0 / frequency
    attrs = run["attrs"]
    print(f"run: {run['history']}")
    print(f"  {text(attrs.get('title', ''))}; status: {text(attrs.get('status', '?'))}; commit "
          f"{text(attrs.get('commit', '?'))}; threads {int(attrs.get('threads', 0)) or '?'}; wall time "
          f"{float(attrs.get('wall_time', float('nan'))):.0f} s")
    print(f"  phase {args.phase!r} from t = {run['start']:.4g} s, at penetration "
          f"{1e3 * run['start_penetration']:.1f} mm (not counted below); run reaches "
          f"{run['time'][-1]:.4g} s of it; cycle {period:g} s")
    print()
    print("| t (s) | cycles | computed (mm) | experiment (mm) | CEL mu = 0.25 (mm) | computed / experiment |")
    print("|---|---|---|---|---|---|")
    rows = penetration_rows(run, period)
    for t, cycles, mm, centre in rows:
        measured = MEASURED_MM.get(t)
        shown = fmt(mm) if centre is None or abs(centre - t) < 1e-9 else f"{fmt(mm)} ({centre:.3f} s)"
        ratio = fmt(mm / measured, 2) if mm is not None and measured else "-"
        print(f"| {t:.2f} | {cycles:.0f} | {shown} | {fmt(measured)} | {fmt(CEL_MM.get(t))} | {ratio} |")

    if args.expect:
        computed = {round(t, 6): mm for t, _, mm, _ in rows}
        failures = []
        for item in args.expect:
            at, _, band = item.partition("=")
            t = round(float(at), 6)
            if t not in MEASURED_MM:
                raise SystemExit(f"--expect {item}: no measured penetration at {at} s")
            mm = computed.get(t)
            if mm is None or not abs(mm / MEASURED_MM[t] - 1.0) <= float(band):
                failures.append(f"at {at} s {fmt(mm)} mm against the measured {MEASURED_MM[t]:.1f} "
                                f"(band {band})")
        print("vibratory check: " + ("ok" if not failures else "FAILED: " + "; ".join(failures)))
        return 1 if failures else 0

    name = nearest_monitor(run["monitors"], tuple(args.ppt_a))
    print()
    if name is None:
        print("no monitor records a pore pressure: no PPT A column")
        print_tip(run, period)
        if args.tip_zone:
            print_tip_zone(run, args.tip_zone)
        return 0
    (r, y), pore = run["monitors"][name]
    print(f"pore pressure at monitor {name!r}, started at (r, y) = ({r:.4f}, {y:.4f}) m, "
          f"{1e3 * math.dist((r, y), tuple(args.ppt_a)):.1f} mm from PPT A's assumed "
          f"({args.ppt_a[0]:g}, {args.ppt_a[1]:g}); compression positive, kPa:")
    print()
    print("| t (s) | computed min / max | computed mean | measured min / max | "
          "CEL mu = 0.25 min / max |")
    print("|---|---|---|---|---|")
    for ((a, b), low, high, mean), measured, cel in zip(pore_rows(run["time"], pore),
                                                        PPT_MEASURED_KPA, PPT_CEL_KPA):
        print(f"| {a:g}-{b:g} | {fmt(low)} / {fmt(high)} | {fmt(mean)} | "
              f"{measured[0]:.1f} / {measured[1]:.1f} | {cel[0]:.1f} / {cel[1]:.1f} |")
    print_tip(run, period)
    if args.tip_zone:
        print_tip_zone(run, args.tip_zone)
    return 0


def print_tip(run, period):
    print()
    print("what carries the tip (window means):")
    print()
    print("| t (s) | mm a cycle | tip F_y (N/rad) | carried by the pore pressure |")
    print("|---|---|---|---|")
    for (a, b), rate, total, share in tip_rows(run, period):
        print(f"| {a:g}-{b:g} | {rate:.2f} | {fmt(total)} | "
              f"{'-' if share is None else f'{100 * share:.0f} %'} |")


if __name__ == "__main__":
    sys.exit(main())
