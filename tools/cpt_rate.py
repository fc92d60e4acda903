#!/usr/bin/python3
"""Penetration rate effects of a saturated CPT: q_c / q_c(drained) against V = v d / c_v.

Each run is given as PATH:K, PATH a history.h5 (or its run directory) of the CPT chamber and K its
hydraulic conductivity in m/s, or "drained" or "undrained" for the two limits (both required).
q_c is the mean over a window of penetration (tools/cpt.py); V takes the cone's velocity v, its
diameter d and c_v = k E_oed / gamma_w with the sand's oedometer modulus E_oed at the chamber's
stress. Prints a Markdown table, with each run's steps and wall time, fits the backbone form

    (q_c - q_c,u) / (q_c,d - q_c,u) = 1 / (1 + (V / V_50)^m)

(V_50 the V at half of the change) to the partially drained runs, and with --figure draws the
runs, the fit and any published curves given as --backbone "LABEL:V50:M".

    tools/cpt_rate.py out/dry:drained out/und:undrained out/sweeps/cpt_rate/variants/v01:1e-3 ... \\
        --eoed 31.9e6 --velocity 0.5 --depth 0.1 --figure docs/figures/cpt_rate.png
"""
import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cpt import cpt_series, window  # noqa: E402

GAMMA_W = 9.81e3  # N/m^3, the unit weight of water in Darcy's law


def backbone(v, v50, m):
    return 1.0 / (1.0 + (v / v50) ** m)


def fit_backbone(speeds, normalised):
    """Least squares over a grid in log V_50 and m: four or so points need nothing finer."""
    best = (np.inf, np.nan, np.nan)
    for v50 in np.logspace(-3, 3, 601):
        for m in np.linspace(0.3, 3.0, 271):
            error = np.sum((backbone(speeds, v50, m) - normalised) ** 2)
            if error < best[0]:
                best = (error, v50, m)
    return best[1], best[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="PATH:K with K in m/s, 'drained' or 'undrained'")
    parser.add_argument("--eoed", type=float, required=True, help="E_oed at the chamber's stress (Pa)")
    parser.add_argument("--velocity", type=float, default=0.02, help="cone velocity (m/s)")
    parser.add_argument("--diameter", type=float, default=0.0357, help="cone diameter (m)")
    parser.add_argument("--depth", type=float, default=0.1, help="penetration of q_c (m)")
    parser.add_argument("--half-window", type=float, default=0.01, help="q_c's mean over +- this (m)")
    parser.add_argument("--backbone", action="append", default=[], help="LABEL:V50:M, drawn")
    parser.add_argument("--figure", help="PNG of q_c / q_c,drained against V")
    args = parser.parse_args()

    limits, partial = {}, []
    for item in args.runs:
        path, _, k = item.rpartition(":")
        history = Path(path)
        if history.is_dir():
            history = history / "history.h5"
        penetration, q_c, _ = cpt_series(str(history), "cone", args.diameter / 2.0, 0.1337)
        value = window(penetration, q_c, args.depth, args.half_window)
        if not np.isfinite(value):
            sys.exit(f"{history}: no q_c within {args.half_window} m of {args.depth} m")
        with h5py.File(history, "r") as f:  # the run's cost, from its last row
            cost = (int(f["/step"][-1]), float(f["/wall_time"][-1]))
        if k in ("drained", "undrained"):
            limits[k] = (value, cost)
        else:
            partial.append((float(k), value, cost))
    if set(limits) != {"drained", "undrained"}:
        sys.exit("give both limits, PATH:drained and PATH:undrained")
    (drained, drained_cost), (undrained, undrained_cost) = limits["drained"], limits["undrained"]
    partial.sort(reverse=True)
    ks = np.array([k for k, _, _ in partial])
    q = np.array([value for _, value, _ in partial])
    costs = [cost for _, _, cost in partial]
    speeds = args.velocity * args.diameter / (ks * args.eoed / GAMMA_W)
    normalised = (q - undrained) / (drained - undrained)
    v50, m = fit_backbone(speeds, normalised) if len(partial) >= 2 else (np.nan, np.nan)

    print(f"q_c at {args.depth} m (mean over +- {args.half_window} m); "
          f"c_v = k E_oed / gamma_w, E_oed = {args.eoed / 1e6:.3g} MPa\n")
    def spent(cost):
        return f"{cost[0]:,}".replace(",", " ") + f" | {cost[1]:.0f}"

    print("| k (m/s) | V | q_c (MPa) | q_c / q_c,drained | (q_c - q_c,u) / (q_c,d - q_c,u) "
          "| steps | wall (s) |")
    print("|---|---|---|---|---|---|---|")
    print(f"| drained | 0 | {drained / 1e6:.2f} | 1 | 1 | {spent(drained_cost)} |")
    for k, v, value, x, cost in zip(ks, speeds, q, normalised, costs):
        print(f"| {k:.0e} | {v:.3g} | {value / 1e6:.2f} | {value / drained:.2f} | {x:.2f} "
              f"| {spent(cost)} |")
    print(f"| undrained | infinite | {undrained / 1e6:.2f} | {undrained / drained:.3f} | 0 "
          f"| {spent(undrained_cost)} |")
    print(f"\nfit: V_50 = {v50:.3g}, m = {m:.2f}")

    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        grid = np.logspace(-3, 3, 300)
        ratio = undrained / drained
        ax.semilogx(speeds, q / drained, "ko", label="mpile, coarse chamber")
        ax.axhline(1.0, color="0.6", lw=0.8, ls=":")
        ax.axhline(ratio, color="0.6", lw=0.8, ls=":")
        ax.text(1.2e-3, 1.0, "drained", va="bottom", fontsize=8)
        ax.text(1.2e-3, ratio, "undrained", va="bottom", fontsize=8)
        if np.isfinite(v50):
            ax.semilogx(grid, ratio + (1 - ratio) * backbone(grid, v50, m), "k-", lw=1,
                        label=f"fit: V50 = {v50:.2g}, m = {m:.2f}")
        for item in args.backbone:
            label, b50, bm = item.rsplit(":", 2)
            ax.semilogx(grid, ratio + (1 - ratio) * backbone(grid, float(b50), float(bm)), "--",
                        lw=1, label=label)
        ax.set_xlabel("V = v d / c_v")
        ax.set_ylabel("q_c / q_c,drained")
        ax.set_ylim(0, 1.1)
        ax.legend(fontsize=8, loc="lower left")
        fig.tight_layout()
        fig.savefig(args.figure, dpi=120)
        print(args.figure)
    return 0


if __name__ == "__main__":
    sys.exit(main())
