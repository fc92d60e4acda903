#!/usr/bin/python3
"""tools/plot_monopile.py's friction-ratio figures (5 and 6): a curve lying exactly on the dashed line
of the contact friction coefficient must stay in view.

  tests/plot_monopile_test.py OUT_DIR

The synthetic run of tests/make_monopile_history.py (written here) has |F_y| / |F_r| = 0.4 and
sqrt(F_y^2 + F_theta^2) / |F_r| = 0.5 on both shafts all along, so figure 5 with mu = 0.4 and figure 6
with mu = 0.5 put the whole curve on the line. Checked, on each shaft of both figures:

- the line at mu is drawn beneath every curve (a lower z-order), in a lighter colour than black;
- each curve carries markers, at rows that differ from run to run (two runs of the same data: their
  markers must not coincide) and in shapes that differ;
- drawn at 300 dpi with one run, the pixels along mu over the curve's span take the curve's colour
  (more than 95 % of them; with the black dashed line drawn over the curve, as before, 28 % did,
  the dashes covering the rest).

Prints "all ok" at the end.
"""
import importlib.util
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_monopile_history import write_history  # noqa: E402

TOOL = Path(__file__).resolve().parent.parent / "tools" / "plot_monopile.py"
SURFACES = ["tip", "external_shaft", "internal_shaft"]
SHAFTS = [SURFACES[2], SURFACES[1]]
# Figure, which ratio, its value all along the synthetic run (= the mu drawn).
FIGURES = (("fig5", 0, 0.4), ("fig6", 1, 0.5))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    write_history(out / "history.h5")

    spec = importlib.util.spec_from_file_location("plot_monopile", TOOL)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    plt, colors = tool.plt, tool.matplotlib.colors
    failures = []

    def check(condition, text):
        print(("ok    " if condition else "FAIL  ") + text)
        if not condition:
            failures.append(text)

    runs = [tool.load(f"{out}:{label}", "pile", SURFACES) for label in ("jacked", "again")]
    for name, which, mu in FIGURES:
        figure = tool.draw_ratio_figure(runs, which, name, SHAFTS, mu, 0.0)
        for ax in figure.axes:
            where = f"{name}, {ax.get_title()}:"
            lines = ax.get_lines()
            friction = [line for line in lines if line.get_label().startswith("contact friction")]
            curves = [line for line in lines if line not in friction]
            check(len(friction) == 1 and len(curves) == 2, f"{where} one line at mu and two curves")
            if len(friction) != 1 or len(curves) != 2:
                continue
            line = friction[0]
            check(np.allclose(line.get_ydata(), mu), f"{where} the line at mu is at {mu}")
            below = all(line.get_zorder() < curve.get_zorder() for curve in curves)
            check(below, f"{where} the line at mu (z-order {line.get_zorder():g}) is beneath the curves "
                  f"(z-orders {', '.join(f'{curve.get_zorder():g}' for curve in curves)})")
            grey = np.mean(colors.to_rgb(line.get_color()))
            check(grey > 0.3, f"{where} the line at mu is lighter than black (grey level {grey:.2f})")
            on_mu = [np.allclose(curve.get_ydata()[np.isfinite(curve.get_ydata())], mu) for curve in curves]
            check(all(on_mu), f"{where} both curves lie on mu all along (the case the figure must show)")
            marks = [list(curve.get_markevery() or []) for curve in curves]
            shapes = [curve.get_marker() for curve in curves]
            check(all(shape not in (None, "", "None", " ") for shape in shapes) and all(len(m) >= 5 for m in marks),
                  f"{where} each curve carries markers ({', '.join(map(str, map(len, marks)))} of them)")
            check(not set(marks[0]) & set(marks[1]) and shapes[0] != shapes[1],
                  f"{where} the two runs' markers at different rows, in shapes {shapes[0]!r} and {shapes[1]!r}")
        plt.close(figure)

        # One run, drawn: the row of pixels at mu, across the middle 80 % of the curve's span.
        figure = tool.draw_ratio_figure(runs[:1], which, name, SHAFTS, mu, 0.0)
        figure.set_dpi(300)
        figure.canvas.draw()
        image = np.asarray(figure.canvas.buffer_rgba())[..., :3].astype(float) / 255.0
        curve_rgb = np.array(colors.to_rgb("C0"))
        for ax in figure.axes:
            penetration = runs[0].penetration
            start, stop = np.percentile(penetration, [10, 90])
            (x0, y), (x1, _) = ax.transData.transform([(start, mu), (stop, mu)])
            row = int(round(image.shape[0] - y - 0.5))
            pixels = image[row, int(np.ceil(x0)):int(np.floor(x1))]
            share = np.mean(np.linalg.norm(pixels - curve_rgb, axis=1) < 0.15)
            check(share > 0.95, f"{name}, {ax.get_title()}: {share:.1%} of {len(pixels)} pixels along mu "
                  f"take the curve's colour (> 95 %)")
        plt.close(figure)

    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("all ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
