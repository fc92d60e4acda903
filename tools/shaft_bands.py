#!/usr/bin/python3
"""The soil beside the outer shaft of cycled piles, in bands (mpile.shaft_bands): how the cycles
change its radial effective stress, void ratio and excess pore pressure, by depth and by distance
from the wall, and how far from the wall they reach.

  tools/shaft_bands.py out/cycles_hs:"HS" out/cycles_hypo:"hypoplastic" --frequency 60 \
      --plot docs/figures/shaft_bands.png

For each run (PATH[:LABEL], a run with particle snapshots, best one a cycle) it prints
  - the band next to the wall (its first distance band) at each depth band: sigma'_r / sigma'_r0,
    the change of void ratio and the excess pore pressure (kPa, compression positive) at cycles
    1, 2, 5, 10, 20, 40 and the last snapshot;
  - the last snapshot's profile against distance from the wall at each depth band;
  - the cyclic zone's reach at each depth band: the outer edge of the farthest band whose
    sigma'_r has moved more than --threshold (10 %) from its value before cycling.
Cycles count from the start of the last phase at --frequency; the first snapshot at or after it
is the state before cycling, and the others are compared at the phase of the cycle most of them
share (a last snapshot elsewhere in its cycle is left out). --plot draws sigma'_r / sigma'_r0 in the wall's band against cycles
(a line per depth, a panel per run) and the last profiles against distance.

The bands default to the quick mesh beside the seed's pile (outer radius 0.373 m, 0.05 m cells,
ground at y = 10 m): depths 0.5 to 1.5, 1.5 to 2.5 m; distances 0, 0.05, 0.1, 0.2, 0.4, 0.8, 1.6 m.
Uses Debian's python3-h5py, -numpy, -xarray and -matplotlib and the mpile package (python/).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

REPOSITORY = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPOSITORY / "python"))
import mpile  # noqa: E402
from mpile.files import RunFileError  # noqa: E402

SHOWN = (1, 2, 5, 10, 20, 40)


def cycled_bands(path, args):
    """The run's bands from the start of its last phase, with a `cycle` coordinate."""
    bands = mpile.shaft_bands(path, args.wall, args.surface, args.depths, args.distances)
    start = float(mpile.phases(path).iloc[-1]["start"])
    bands = bands.where(bands["time"] >= start - 1e-9, drop=True)
    if bands.sizes["time"] < 2:
        raise RunFileError(f"{path}: fewer than two snapshots in its last phase")
    cycle = np.round((bands["time"].values - start) * args.frequency, 6)
    bands = bands.assign_coords(cycle=("time", cycle))
    # Compared at one phase of the cycle: the snapshots on the output's clock share one, while one
    # at the phase's end (the run's last) may fall elsewhere in its cycle, where the stress swings.
    phase = np.mod(cycle[1:], 1.0)
    usual = float(np.median(phase))
    keep = np.concatenate([[True], np.abs(phase - usual) < 0.02])
    return bands.isel(time=np.flatnonzero(keep))


def changes(bands):
    """sigma'_r / sigma'_r0, e - e_0 and the excess pore pressure (kPa), on (time, depth, distance)."""
    first = bands.isel(time=0)
    found = {"sigma_r / sigma_r0": bands["sigma_r"] / first["sigma_r"],
             "e - e0": bands["void_ratio"] - first["void_ratio"],
             "excess u (kPa)": bands["excess_pore_pressure"] / 1e3}
    # A run without void ratio (Hardening Soil) or pore water (dry) has none of those.
    return {name: values for name, values in found.items() if bool(np.isfinite(values).any())}


def reach(ratio, edges, threshold):
    """The outer edge of the farthest band whose ratio moved more than threshold, per depth."""
    moved = np.abs(ratio - 1.0) > threshold
    out = []
    for row in moved:
        beyond = np.flatnonzero(row)
        out.append(edges[beyond[-1] + 1] if beyond.size else 0.0)
    return out


def report(label, bands, args):
    quantities = changes(bands)
    depths = [f"{top:g}-{bottom:g} m" for top, bottom in args.depths]
    cycles = bands["cycle"].values
    # The snapshot nearest each shown cycle count (snapshots fall on the output's clock, not
    # necessarily on whole cycles of the phase), and the last.
    rows = [int(np.argmin(np.abs(cycles - n))) for n in SHOWN if abs(cycles - n).min() <= 0.5]
    rows.append(len(cycles) - 1)
    print(f"{label}: the band next to the wall ({args.distances[0]:g} to {args.distances[1]:g} m)")
    print()
    print("| cycle | " + " | ".join(f"{q}, {d}" for q in quantities for d in depths) + " |")
    print("|---|" + "---|" * (len(quantities) * len(depths)))
    for i in dict.fromkeys(rows):
        cells = [f"{float(v.isel(time=i, distance=0, depth=k)):.3g}"
                 for v in quantities.values() for k in range(len(depths))]
        print(f"| {cycles[i]:.2f} | " + " | ".join(cells) + " |")
    print()
    edges = args.distances
    print(f"{label}: after {cycles[-1]:.2f} cycles, against distance from the wall (m)")
    print()
    print("| quantity, depth | " + " | ".join(f"{a:g}-{b:g}" for a, b in zip(edges, edges[1:])) + " |")
    print("|---|" + "---|" * (len(edges) - 1))
    for name, values in quantities.items():
        for k, depth in enumerate(depths):
            cells = [f"{float(v):.3g}" for v in values.isel(time=-1, depth=k).values]
            print(f"| {name}, {depth} | " + " | ".join(cells) + " |")
    print()
    ratio = quantities["sigma_r / sigma_r0"].isel(time=-1).values
    reaches = reach(ratio, edges, args.threshold)
    print(f"{label}: sigma'_r moved more than {100 * args.threshold:g} % out to "
          + ", ".join(f"{r:g} m ({d})" for r, d in zip(reaches, depths)) + " from the wall")
    print()


def plot(runs, args):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(2, len(runs), figsize=(5.5 * len(runs), 8), squeeze=False)
    for column, (label, bands) in enumerate(runs):
        ratio = changes(bands)["sigma_r / sigma_r0"]
        top, bottom = axes[0][column], axes[1][column]
        for k, (a, b) in enumerate(args.depths):
            top.plot(bands["cycle"], ratio.isel(depth=k, distance=0), label=f"{a:g} to {b:g} m deep")
            bottom.plot(bands["distance"], ratio.isel(time=-1, depth=k), marker="o",
                        label=f"{a:g} to {b:g} m deep")
        top.axhline(1.0, color="0.6", linewidth=0.8)
        bottom.axhline(1.0, color="0.6", linewidth=0.8)
        top.set(title=label, xlabel="cycles", ylabel="sigma'_r / sigma'_r0 beside the wall")
        bottom.set(xscale="log", xlabel="distance from the wall (m), band mid-points",
                   ylabel=f"sigma'_r / sigma'_r0 after {bands['cycle'].values[-1]:.0f} cycles")
        top.legend()
        bottom.legend()
    figure.tight_layout()
    figure.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")


def pairs(text):
    values = [float(v) for v in text.split(",")]
    if len(values) % 2:
        raise argparse.ArgumentTypeError("give depth bands as top,bottom,top,bottom,...")
    return list(zip(values[::2], values[1::2]))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="PATH[:LABEL]")
    parser.add_argument("--frequency", type=float, required=True, help="the cycles' frequency (Hz)")
    parser.add_argument("--wall", type=float, default=0.373, help="the wall's radius (m)")
    parser.add_argument("--surface", type=float, default=10.0, help="the ground's y (m)")
    parser.add_argument("--depths", type=pairs, default=[(0.5, 1.5), (1.5, 2.5)])
    parser.add_argument("--distances", type=lambda t: [float(v) for v in t.split(",")],
                        default=[0.0, 0.05, 0.1, 0.2, 0.4, 0.8, 1.6])
    parser.add_argument("--threshold", type=float, default=0.1)
    parser.add_argument("--plot")
    args = parser.parse_args(argv)
    runs = []
    try:
        for spec in args.runs:
            path, _, label = spec.partition(":")
            bands = cycled_bands(path, args)
            report(label or path, bands, args)
            runs.append((label or path, bands))
    except (RunFileError, ValueError) as e:
        print(f"shaft_bands.py: {e}", file=sys.stderr)
        return 2
    if args.plot:
        plot(runs, args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
