#!/usr/bin/python3
"""Capacity after installation: the load-settlement curves of load-test runs in one figure, and a
Markdown table of each run's load at 0, 10, 25 and 50 mm of settlement and its capacity at a
settlement of 10 % of the diameter (docs/results.md, "Capacity after installation").

  tools/capacity.py out/jacked_quick_capacity:jacked out/gdp_quick_capacity:GDP --out capacity.png

A run is a directory or history.h5 whose last phase is the load test, optionally with :label
(default: the run's title). The capacity is in kN/rad and, times 2 pi, in MN for the whole pile;
beside it the soil's upward force on the tip and each shaft there (their sum is the load plus the
pile's weight). With --zone F, a second table: how far the sand the test moved by at least F of its
settlement reaches (below the tip, out from the wall, above the tip outside it) and how much of the
settlement the plug followed, from the snapshots at the test's start and end. With --installed as
well, a third: how deep below the final tip and how far out from the wall the installation (the
phase named installation) moved sand by that same distance. With --fill, how many times over the
soil particles fill the zones a wall thickness below the wall's tip (under it, inside and outside)
at each snapshot: crowded particles fill them more than once. With --record, a table of what each
run cost and how its ledger closed: the depth and time its installation reached, how long it rested,
its steps and wall time (across continuations), and its energy residual after the installation and
at the end.

With --curves DIR each run's curve is also written as DIR/<label>.csv.gz (settlement, load and the
surfaces' forces, with the run's case and commit in its header); such a CSV is a run too, for
the figure and the first table, so that a figure of runs that take hours is drawn again without
them (the zone tables need the run's snapshots and leave it out).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))

from mpile.capacity import (CAPACITY_SETTLEMENT, installation_reach, load_test, load_test_zone,  # noqa: E402
                            run_record, wall_tip_fills, write_load_test_csv)
from mpile.history import attributes  # noqa: E402
from mpile.files import RunFileError  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="run directory or history.h5, optionally :label")
    parser.add_argument("--out", default="capacity.png", help="the figure (PNG)")
    parser.add_argument("--zone", type=float, metavar="F", help="also the zone the test moved by F of its settlement")
    parser.add_argument("--installed", action="store_true",
                        help="with --zone, also where the installation moved the sand by as much")
    parser.add_argument("--fill", action="store_true",
                        help="also how many times over the particles fill the zones at the wall's tip")
    parser.add_argument("--record", action="store_true",
                        help="also each run's installation, steps, wall time and ledger")
    parser.add_argument("--curves", metavar="DIR", help="also write each history run's curve as DIR/<label>.csv.gz")
    args = parser.parse_args()
    if args.installed and args.zone is None:
        parser.error("--installed measures at the distance --zone F sets: give --zone")
    tests, zones, reaches, records, fills = [], [], [], [], []
    try:
        for run in args.runs:
            path, _, label = run.partition(":")
            tests.append(load_test(path, label=label or None))
            if path.endswith((".csv", ".csv.gz")):
                continue
            if args.curves:
                os.makedirs(args.curves, exist_ok=True)
                name = "".join(c if c.isalnum() else "_" for c in tests[-1].label).strip("_") + ".csv.gz"
                attrs = attributes(path)
                sets = " ".join(f"--set {o}" for o in str(attrs.get("overrides", "")).split("\n") if o)
                write_load_test_csv(tests[-1], os.path.join(args.curves, name),
                                    f"mpile run {attrs.get('case_file', '?')} {sets} at {attrs.get('commit', '?')}")
            if args.zone is not None:
                zones.append((tests[-1], load_test_zone(path, args.zone)))
            if args.record:
                records.append((tests[-1], run_record(path)))
            if args.fill:
                fills.append((tests[-1], wall_tip_fills(path)))
            if args.zone is not None and args.installed:
                distance = args.zone * tests[-1].settlement.max()
                reaches.append((tests[-1], installation_reach(path, distance)))
    except (RunFileError, KeyError) as e:
        print(f"capacity.py: {e}", file=sys.stderr)
        return 2
    surfaces = ("tip", "external_shaft", "internal_shaft")
    print("| run | settlement reached (m) | load at 0 / 10 / 25 / 50 mm (kN/rad) | load at 10 % of D (kN/rad) | "
          "whole pile (MN) | tip / external / internal F_y there (kN/rad) | ended |")
    print("|---|---|---|---|---|---|---|")
    for t in tests:
        q = t.capacity
        shares = t.shares
        split = " / ".join(f"{shares[name]:.1f}" if name in shares else "-" for name in surfaces)
        curve = " / ".join(f"{t.load_at(s):.1f}" for s in (0.0, 0.010, 0.025, 0.050))
        print(f"| {t.label} | {t.settlement.max():.4f} | {curve} | {q:.1f} | {2 * math.pi * q / 1e3:.3g} | {split} "
              f"| {t.ended} |")
    if zones:
        print()
        print(f"| run | moved by {args.zone:g} of the settlement: below the tip (m) | out from the wall (m) | "
              "above the tip outside (m) | plug's settlement / pile's |")
        print("|---|---|---|---|---|")
        for t, z in zones:
            print(f"| {t.label} | {z.below_tip:.2f} | {z.outside_wall:.2f} | {z.above_tip_outside:.2f} | {z.plug_follows:.2f} |")
    if reaches:
        print()
        print("| run | the installation moved by as much (mm): below the tip at its end (m) | out from the wall (m) |")
        print("|---|---|---|")
        for t, z in reaches:
            print(f"| {t.label} | {1e3 * z.distance:.1f}: {z.below_tip:.2f} | {z.outside_wall:.2f} |")
    if records:
        print()
        print("| run | installed to (m) at (s) | rest (s) | steps | wall (s) | "
              "ledger after the installation / at the end |")
        print("|---|---|---|---|---|---|")
        for t, r in records:
            steps, wall = (f"{n:,.0f}".replace(",", " ") for n in (r.steps, r.wall_time))
            print(f"| {t.label} | {r.depth:.3f} at {r.installed_at:.3f} | {r.rest:.3g} | {steps} | {wall} | "
                  f"{100 * r.ledger_installed:#.2g} / {100 * r.ledger_end:#.2g} % |")
    if fills:
        print()
        print("| run | t (s) | the particles fill the zone a wall thickness below the tip: under the wall / "
              "inside / outside (times) |")
        print("|---|---|---|")
        for t, run_fills in fills:
            for f in run_fills:
                print(f"| {t.label} | {f.time:.3f} | {f.under:.2f} / {f.inside:.2f} / {f.outside:.2f} |")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6, 4.5))
    for t in tests:
        axes.plot(1e3 * t.settlement, t.load, label=t.label)
    diameters = {t.diameter for t in tests if math.isfinite(t.diameter)}
    if len(diameters) == 1:
        axes.axvline(1e3 * CAPACITY_SETTLEMENT * diameters.pop(), color="grey", linestyle=":",
                     label="10 % of D")
    axes.set_xlabel("settlement since the load test began (mm)")
    axes.set_ylabel("load on the pile head (kN/rad)")
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=120)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
