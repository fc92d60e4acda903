#!/usr/bin/python3
"""Draw the seed paper's figure 1b from a V9 run: the theta reactions of the soil on the pile's
internal shaft, external shaft and base against time, with the analytical values
c_a r h (2 and 3 kN/rad) and c_a (r2^2 - r1^2) / 2 (1 kN/rad), and print the means over 0.5-1 s.

  mpile run cases/verification/v9_torsion_adhesion.toml
  tools/plot_torsion.py out/v9_torsion_adhesion/history.h5 --out docs/figures/v9_torsion.png

Reads the history with the mpile package (python/mpile); uses Debian's python3-h5py, python3-numpy
and python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The mpile package of this repository (python/mpile), so the tool runs without installing it.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
import mpile  # noqa: E402

SURFACES = [("internal_shaft", "internal shaft", 2.0), ("external_shaft", "external shaft", 3.0),
            ("base", "base", 1.0)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("history", help="history.h5 of a V9 run")
    parser.add_argument("--body", default="pile", help="the structure's body name (default pile)")
    parser.add_argument("--out", default="v9_torsion.png", help="PNG file (default v9_torsion.png)")
    args = parser.parse_args()

    names = [f"/reactions/{args.body}/{key}/F_theta" for key, _, _ in SURFACES]
    try:
        series = mpile.read_series(args.history, ["/time"] + names)
    except mpile.RunFileError as error:
        print(f"plot_torsion: {error}", file=sys.stderr)
        return 2
    time = series["/time"]
    steady = (time >= 0.5) & (time <= 1.0)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    total = 0.0
    for (key, label, exact), name in zip(SURFACES, names):
        # The force of the soil on the pile opposes the spin; plotted as a magnitude in kN/rad.
        force = -series[name] / 1e3
        line, = ax.plot(time, force, label=f"{label} (MPM)")
        ax.axhline(exact, color=line.get_color(), linestyle="--", linewidth=0.8,
                   label=f"{label}, analytical {exact:g}")
        mean = force[steady].mean() if steady.any() else float("nan")
        total += mean
        print(f"{label}: mean over 0.5-1 s {mean:.4f} kN/rad, analytical {exact:g}, "
              f"error {100 * (mean - exact) / exact:+.3f} %")
    print(f"sum: {total:.4f} kN/rad, analytical 6, error {100 * (total - 6.0) / 6.0:+.3f} %")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("theta reaction on the pile [kN/rad]")
    ax.set_title("Torsion of an open-ended pile with adhesion c_a = 10 kPa")
    ax.set_ylim(0.0, 3.5)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
