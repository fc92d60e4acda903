#!/usr/bin/python3
"""The saturated installation runs side by side: a Markdown table of forces and pore pressures.

Each run is PATH[:LABEL], PATH a monopile run's directory (history.h5 and run.log). For each
penetration of --at, at the first history row at or past it: the time, the forces of the soil on
the tip (F_y) and on the external and internal shafts (F_r) in kN/rad with the pore water's part
in brackets (the whole pore pressure's, hydrostatic and excess), each shaft's friction over its
effective radial force, sqrt(F_y^2 + F_theta^2) / |F_r - pore F_r| (mu where it slides), and the
excess pore pressure (kPa, compression positive as geotechnical engineers read it: the history's is
tension positive) at the monitors below the tip, in the plug and beside the outer shaft 1 and 2 m
deep (base/seed_monopile.toml). A run that stopped short gives its last penetration.
The run's steps and wall time come from the last row.

    tools/saturated_table.py out/gdp_und:"GDP, undrained" out/gdp_k1e-4:"GDP, k = 1e-4" --at 0.05,0.1

With --figure PNG it also draws the excess pore pressure at the four monitors against time, one
panel per run.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402

MONITORS = ("below_tip", "inside_tip", "outer_shaft_1m", "outer_shaft_2m")


def series(path, names):
    available = {name for name, _, _ in mpile.list_datasets(path)}
    found = [name for name in names if name in available]
    data = mpile.read_series(path, found)
    return {name: data.get(name, np.full(len(data["/time"]), np.nan)) for name in names}


def force(f, surface, component, row, pore=False):
    name = f"/reactions/pile/{surface}/{'pore_' if pore else ''}{component}"
    return f[name][row] / 1e3


def ratio(f, surface, row):
    """The shaft's friction over its effective radial force: mu where it slides."""
    base = f"/reactions/pile/{surface}"
    shear = np.hypot(f[f"{base}/F_y"][row], f[f"{base}/F_theta"][row])
    pore = f[f"{base}/pore_F_r"][row]
    return shear / abs(f[f"{base}/F_r"][row] - (pore if np.isfinite(pore) else 0.0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="PATH[:LABEL]")
    parser.add_argument("--at", type=lambda s: [float(x) for x in s.split(",")], default=[0.05, 0.1])
    parser.add_argument("--figure", help="PNG of the monitors' excess pore pressure against time")
    args = parser.parse_args()
    histories = []
    names = ["/time", "/step", "/wall_time", "/bodies/pile/u_y"]
    for surface in ("tip", "external_shaft", "internal_shaft"):
        for component in ("F_r", "F_y", "F_theta", "pore_F_r", "pore_F_y"):
            names.append(f"/reactions/pile/{surface}/{component}")
    names += [f"/monitors/{m}/excess_pore_pressure" for m in MONITORS]
    header = ("| run | steps | wall (s) | at | time (s) | tip F_y | ext F_r | int F_r | ext ratio "
              "| int ratio | excess u: below tip / plug / shaft 1 m / 2 m (kPa) |")
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for item in args.runs:
        path, _, label = item.partition(":")
        history = Path(path) / "history.h5" if Path(path).is_dir() else Path(path)
        try:
            f = series(str(history), names)
        except mpile.RunFileError as error:
            sys.exit(str(error))
        histories.append((label or path, f))
        penetration = -f["/bodies/pile/u_y"]
        first = True
        for depth in args.at:
            reached = np.nonzero(penetration >= depth)[0]
            row = reached[0] if reached.size else len(penetration) - 1
            at = f"{depth:g} m" if reached.size else f"{penetration[row]:.3f} m (stopped)"
            cells = [label or path, f"{int(f['/step'][-1]):,}".replace(",", " "),
                     f"{f['/wall_time'][-1]:.0f}"] if first else ["", "", ""]
            first = False
            cells += [at, f"{f['/time'][row]:.3f}"]
            for surface, component in (("tip", "F_y"), ("external_shaft", "F_r"),
                                       ("internal_shaft", "F_r")):
                total = force(f, surface, component, row)
                pore = force(f, surface, f"pore_{component}", row)
                cells.append(f"{total:.1f}" + (f" ({pore:.1f})" if np.isfinite(pore) else ""))
            cells += [f"{ratio(f, 'external_shaft', row):.2f}",
                      f"{ratio(f, 'internal_shaft', row):.2f}"]
            excess = [-f[f"/monitors/{m}/excess_pore_pressure"][row] / 1e3 for m in MONITORS]
            cells.append(" / ".join("-" if not np.isfinite(x) else f"{x:.0f}" for x in excess))
            if not reached.size:
                cells[3] = at
                print("| " + " | ".join(cells) + " |")
                break
            print("| " + " | ".join(cells) + " |")
    if args.figure:
        draw(histories, args.figure)
    return 0


def draw(histories, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(histories), 1, figsize=(6.4, 2.2 * len(histories) + 0.6),
                             sharex=False, squeeze=False)
    for ax, (label, f) in zip(axes[:, 0], histories):
        for monitor, name in zip(MONITORS, ("below the tip", "in the plug", "outer shaft, 1 m",
                                            "outer shaft, 2 m")):
            u = -f[f"/monitors/{monitor}/excess_pore_pressure"] / 1e3
            if np.isfinite(u).any():
                ax.plot(f["/time"], u, lw=0.8, label=name)
        ax.set_title(label, fontsize=9)
        ax.set_ylabel("excess u (kPa)")
        ax.grid(alpha=0.3)
    for ax in axes[:, 0]:
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, ncol=2)
            break
    axes[-1, 0].set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(path)


if __name__ == "__main__":
    sys.exit(main())
