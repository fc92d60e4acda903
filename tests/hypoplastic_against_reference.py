#!/usr/bin/env python3
"""The engine's hypoplastic element tests (cases/element_tests/hypoplastic_*.toml, run by `mpile
element-test`) against tools/hypoplastic_reference.py, an independent integration of the same
equations in Python (Dormand-Prince 5(4) at a relative tolerance of 1e-9, tested on its own by
tests/hypoplastic_reference_test.py). Usage: hypoplastic_against_reference.py MPILE OUT_DIR
[--figure PNG]: with --figure, also draws every path, the engine's as lines and the reference's as
markers, to one PNG (docs/figures/hypoplastic/element_tests.png)."""
import csv
import pathlib
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(SOURCE / "tools"))
import hypoplastic_reference as ref  # noqa: E402

# The engine integrates each increment by Heun's method to a relative tolerance of 1e-5 per
# substep (the material's default; h in substeps of its own) over increments of 1e-4 axial strain;
# along these paths its values stay within 3.6e-5 of the reference (measured: the drained cycles'
# volumetric strain after ten cycles; q within 2.7e-5). 1e-4 leaves room for the order in which
# rounding falls, and is far below what a wrong term moves (percents: the reference's own mutation
# tests).
RELATIVE = 1e-4


def run_element_file(mpile, toml_path, out):
    """`mpile element-test` of one file, its CSV read back as rows of numbers."""
    csv_path = out / f"{pathlib.Path(toml_path).stem}.csv"
    subprocess.run([mpile, "element-test", str(toml_path), "--out", str(csv_path)], check=True,
                   stdout=subprocess.DEVNULL)
    with open(csv_path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def element_test(mpile, name, out):
    return run_element_file(mpile, SOURCE / "cases/element_tests" / f"{name}.toml", out)


def row_at(rows, column, value):
    return min(rows, key=lambda row: abs(row[column] - value))


def compare(what, engine, reference, failures):
    error = abs(engine - reference) / abs(reference)
    status = "ok" if error <= RELATIVE else "FAILED"
    print(f"{what}: engine {engine:.9g}, reference {reference:.9g}, relative {error:.2e} {status}")
    if error > RELATIVE:
        failures.append(what)


def draw(curves, png):
    """The paths of `curves` (name -> (engine x, engine y, reference x, reference y)) in panels."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = [
        ("drained triaxial, p0 = 100 kPa", "eps_1 (%)", "q (kPa)", ["dense q", "loose q"], None),
        ("drained triaxial, p0 = 100 kPa", "eps_1 (%)", "eps_v (%), compression > 0",
         ["dense eps_v", "loose eps_v"], None),
        ("oedometer 50 -> 400 -> 100 kPa", "sigma_1 (kPa)", "void ratio", ["oedometer"], "logx"),
        ("drained cycles of eps_1 = +-1e-3", "cycle", "eps_v at the cycle's end (%)",
         ["drained cycles"], None),
        ("undrained cycles, q = +-30 kPa, e0 = 0.85", "p' (kPa)", "q (kPa)", ["butterfly"], None),
        ("secant shear modulus, drained cyclic torsion", "shear strain amplitude", "G / G0",
         ["G/G0"], "logx"),
        ("undrained triaxial, loose (e0 = 1.05), p0 = 100 kPa", "p' (kPa)", "q (kPa)",
         ["static liquefaction"], None),
    ]
    fig, axes = plt.subplots(2, 4, figsize=(19, 8.5))
    axes.flat[-1].set_visible(False)
    for ax, (title, xlabel, ylabel, names, scale) in zip(axes.flat, panels):
        for k, name in enumerate(names):
            ex, ey, rx, ry = curves[name]
            colour = f"C{k}"
            ax.plot(ex, ey, "-", color=colour, lw=1.2 if len(ex) < 2000 else 0.5,
                    label=f"{name}: engine")
            if len(rx) > 2000:  # a long cyclic path: markers would hide it, a dashed line shows it
                ax.plot(rx, ry, "--", color="k", lw=0.6, label=f"{name}: reference")
                continue
            step = max(1, len(rx) // 40)
            ax.plot(rx[::step], ry[::step], "o", color=colour, ms=4, mfc="none",
                    label=f"{name}: reference")
        if scale == "logx":
            ax.set_xscale("log")
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Karlsruhe fine sand: mpile element-test (lines) against "
                 "tools/hypoplastic_reference.py (markers)")
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print(png)


def column(rows, name, scale=1.0):
    return [row[name] * scale for row in rows]


def main():
    mpile, out = sys.argv[1], pathlib.Path(sys.argv[2])
    figure = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--figure" else None
    curves = {}
    out.mkdir(parents=True, exist_ok=True)
    kfs = ref.KARLSRUHE_FINE_SAND
    failures = []

    rows = element_test(mpile, "hypoplastic_dense_triaxial", out)
    r = ref.drained_triaxial(kfs, ref.State.isotropic(100e3, 0.70), 0.3, steps=300)
    curves["dense q"] = (column(rows, "eps_1", 100), column(rows, "q", 1e-3), r["eps_1"] * 100,
                         r["q"] / 1e3)
    curves["dense eps_v"] = (column(rows, "eps_1", 100), column(rows, "eps_v", 100),
                             r["eps_1"] * 100, r["eps_v"] * 100)
    for eps in (0.01, 0.05, 0.3):
        k = int(round(eps / 0.3 * 300))
        row = row_at(rows, "eps_1", eps)
        compare(f"dense triaxial q at eps_1 = {eps}", row["q"], r["q"][k], failures)
        compare(f"dense triaxial e at eps_1 = {eps}", row["void_ratio"], r["e"][k], failures)

    rows = element_test(mpile, "hypoplastic_loose_triaxial", out)
    r = ref.drained_triaxial(kfs, ref.State.isotropic(100e3, 1.05), 0.3, steps=300)
    curves["loose q"] = (column(rows, "eps_1", 100), column(rows, "q", 1e-3), r["eps_1"] * 100,
                         r["q"] / 1e3)
    curves["loose eps_v"] = (column(rows, "eps_1", 100), column(rows, "eps_v", 100),
                             r["eps_1"] * 100, r["eps_v"] * 100)
    for eps in (0.01, 0.3):
        k = int(round(eps / 0.3 * 300))
        row = row_at(rows, "eps_1", eps)
        compare(f"loose triaxial q at eps_1 = {eps}", row["q"], r["q"][k], failures)
        compare(f"loose triaxial eps_v at eps_1 = {eps}", row["eps_v"], r["eps_v"][k], failures)

    rows = element_test(mpile, "hypoplastic_oedometer", out)
    r = ref.oedometer_stress(kfs, ref.State.triaxial(50e3, 25e3, 0.80), [400e3, 100e3], steps=100)
    top = max(range(len(rows)), key=lambda k: rows[k]["sigma_1"])
    curves["oedometer"] = (column(rows, "sigma_1", 1e-3), column(rows, "void_ratio"),
                           r["sigma_1"] / 1e3, r["e"])
    compare("oedometer e at 400 kPa", rows[top]["void_ratio"], r["e"][100], failures)
    compare("oedometer sigma_3 at 400 kPa", rows[top]["sigma_3"], r["sigma_3"][100], failures)
    compare("oedometer e back at 100 kPa", rows[-1]["void_ratio"], r["e"][-1], failures)

    # Undrained monotonic triaxial of the loose sample (static liquefaction), with the water made
    # stiff as in the cyclic test (K_w = 2.2e12 Pa: the shipped file's 2.2e9 lets the sample change
    # volume by about 1 % of what the skeleton's compliance asks, and the reference is isochoric).
    text = (SOURCE / "cases/element_tests/hypoplastic_undrained_triaxial.toml").read_text()
    (out / "undrained_triaxial_isochoric.toml").write_text(text.replace(
        "grain_density = 2650.0", "water_bulk_modulus = 2.2e12\ngrain_density = 2650.0", 1))
    rows = run_element_file(mpile, out / "undrained_triaxial_isochoric.toml", out)
    r = ref.undrained_triaxial(kfs, ref.State.isotropic(100e3, 1.05), 0.05, steps=500)
    curves["static liquefaction"] = ([(row["p"] + row["pore_pressure"]) / 1e3 for row in rows],
                                     column(rows, "q", 1e-3), r["p"] / 1e3, r["q"] / 1e3)
    for eps in (0.006, 0.05):
        k = int(round(eps / 0.05 * 500))
        row = row_at(rows, "eps_1", eps)
        compare(f"undrained loose triaxial q at eps_1 = {eps}", row["q"], r["q"][k], failures)
        compare(f"undrained loose triaxial p' at eps_1 = {eps}", row["p"] + row["pore_pressure"],
                r["p"][k], failures)

    rows = element_test(mpile, "hypoplastic_drained_cycles", out)
    r = ref.drained_strain_cycles(kfs, ref.State.isotropic(100e3, 0.80), 1e-3, 10)
    per_cycle = 200
    ends = range(1, 11)
    curves["drained cycles"] = (list(ends), [rows[n * per_cycle]["eps_v"] * 100 for n in ends],
                                list(ends), [v * 100 for v in r["cycle_eps_v"][:10]])
    for cycle in (1, 5, 10):
        compare(f"drained cycles eps_v after cycle {cycle}", rows[cycle * per_cycle]["eps_v"],
                r["cycle_eps_v"][cycle - 1], failures)

    # Undrained stress-controlled cycles: the excess pore pressure at the end of cycles (q back at
    # 0) and the cycle at which the double amplitude of axial strain reaches 5 %. The engine's q
    # follows a sine, the reference's straight ramps between the same turning points; the model is
    # rate independent, so the two meet at every q. The reference counts a cycle's part by |q|
    # moved, a quarter per amplitude; the engine's row at liquefaction is converted to that count.
    rows = element_test(mpile, "hypoplastic_undrained_cycles", out)
    amplitude, p0 = 30e3, 100e3
    r = ref.undrained_cyclic_triaxial(kfs, ref.State.isotropic(p0, 0.85), amplitude, 60,
                                      eps_da=0.05)
    curves["butterfly"] = ([(row["p"] + row["pore_pressure"]) / 1e3 for row in rows],
                           column(rows, "q", 1e-3), r["p"] / 1e3, r["q"] / 1e3)
    ends = [row for row in rows if row["cycle"] > 0 and abs(row["cycle"] - round(row["cycle"])) < 1e-9]
    for cycle in (1, 10, 20, 30):
        row = ends[cycle - 1]
        excess = p0 - (row["p"] + row["pore_pressure"])
        compare(f"undrained cycles: excess pore pressure after cycle {cycle}", excess,
                r["cycle_du"][cycle - 1], failures)
    last = rows[-1]
    quarter = int(last["cycle"] * 4.0 + 1e-9)
    start = (0.0, amplitude, 0.0, -amplitude)[quarter % 4]
    counted = (quarter + abs(last["q"] - start) / amplitude) / 4.0
    # The engine stops at the first increment past 5 % (1e-3 of a cycle each); the reference at
    # the crossing itself.
    error = abs(counted - r["n_liq"])
    status = "ok" if error <= 2e-3 else "FAILED"
    print(f"undrained cycles to liquefaction: engine {counted:.5f}, reference {r['n_liq']:.5f}, "
          f"difference {error:.1e} cycles {status}")
    if error > 2e-3:
        failures.append("cycles to liquefaction")

    # The decay of the secant shear modulus with the shear strain amplitude: drained cyclic torsion
    # (gamma_ytheta prescribed, normal stresses held) 0 -> +A -> -A -> +A, G = (tau(+A) - tau(-A)) /
    # (2 A) on the reloading branch: the engine's sine passes the same turning points (rows 5 n / 4
    # and 3 n / 4 of its 2 cycles of n increments), and the model is rate independent.
    template = (SOURCE / "cases/element_tests/hypoplastic_shear_modulus.toml").read_text()
    amplitudes = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2]
    r = ref.shear_modulus_decay(kfs, ref.State.isotropic(100e3, 0.80), amplitudes, steps=200)
    engine_ratio = []
    for amplitude, reference_g in zip(amplitudes, r["G_sec"]):
        name = f"shear_modulus_{amplitude:g}"
        (out / f"{name}.toml").write_text(template.replace(
            "shear_strain_amplitude = 1e-4", f"shear_strain_amplitude = {amplitude:g}"))
        table = run_element_file(mpile, out / f"{name}.toml", out)
        n = 400
        secant = (table[5 * n // 4]["tau_ytheta"] - table[3 * n // 4]["tau_ytheta"]) / (2.0 * amplitude)
        engine_ratio.append(secant / r["G0"])
        compare(f"shear modulus G/G0 at gamma = {amplitude:g} (G0 = {r['G0'] / 1e6:.2f} MPa)",
                secant / r["G0"], reference_g / r["G0"], failures)

    curves["G/G0"] = (amplitudes, engine_ratio, amplitudes, list(r["G_ratio"]))
    if figure:
        draw(curves, figure)
    if failures:
        print(f"{len(failures)} comparison(s) outside {RELATIVE:g}: {', '.join(failures)}")
        return 1
    print("all within", RELATIVE)
    return 0


if __name__ == "__main__":
    sys.exit(main())
