#!/usr/bin/python3
"""The energy ledger of a rigid footing pushed into soil, row by row, and its bearing pressure.

  tools/footing_ledger.py out/footing_tresca                     # read a run's history.h5
  tools/footing_ledger.py --run cases/verification/footing_tresca.toml --out /tmp/f \
      [--set contact.0.adhesion=20e3 ...]                        # run it first (one thread)

Prints per history row: time, the footing's settlement, its base pressure q (the base's F_y over
its plan area) and q / c, the ledger's terms (external work, kinetic energy's change, internal
work, contact, transfer, damping, residual and relative residual) and, as a check of the external
work, the footing's driving work integrated from the history (driving_F_y times v_y, trapezoidal
over the rows, so only as exact as the rows are dense) and the soil's side of the books
(internal work + kinetic change + contact + transfer + damping); then the mean of q / c over bands
of settlement (the base pressure swings as the base crosses grid lines) against a circle's limit on
Tresca soil. Reads the history with the mpile package (python/mpile); needs Debian's python3-h5py
(/usr/bin/python3).
"""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))
import mpile  # noqa: E402

import h5py  # noqa: E402

# Limit pressures of a circular footing on a Tresca half-space, in units of c: smooth 5.69
# (Shield 1955), rough 6.05 (Eason & Shield 1960); a strip's (2 + pi) for comparison (Prandtl).
CIRCLE_SMOOTH = 5.69
CIRCLE_ROUGH = 6.05


def run(case, out, sets, mpile_binary, threads):
    command = [str(mpile_binary), "run", str(case), "--threads", str(threads), "--out", str(out)]
    for s in sets:
        command += ["--set", s]
    print("#", " ".join(command), flush=True)
    done = subprocess.run(command, capture_output=True, text=True)
    tail = (done.stdout + done.stderr).strip().splitlines()[-3:]
    for line in tail:
        print("#", line)
    return done.returncode


def material_cohesion(history_file, body):
    """The cohesion of the soil's material from the resolved case text (for q / c)."""
    try:
        import tomllib
    except ImportError:  # pragma: no cover
        return None, None, {}
    with h5py.File(history_file, "r") as f:
        text = f.attrs.get("case_resolved", f.attrs.get("case_text", ""))
    if isinstance(text, bytes):
        text = text.decode()
    case = tomllib.loads(text)
    soils = [b for b in case.get("bodies", []) if "rigid" not in b]
    for b in soils:
        material = case["materials"].get(b["material"], {})
        if "cohesion" in material:
            return float(material["cohesion"]), material.get("type"), case
    return None, None, case


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("path", nargs="?", help="a run's output directory or history.h5")
    parser.add_argument("--run", help="run this case file first (into --out)")
    parser.add_argument("--out", help="output directory for --run")
    parser.add_argument("--set", action="append", default=[], help="a --set for mpile run (repeatable)")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--mpile", default=str(ROOT / "build" / "release" / "bin" / "mpile"))
    parser.add_argument("--body", default="footing", help="the rigid footing's body name")
    parser.add_argument("--surface", default="base", help="its base's contact surface")
    parser.add_argument("--every", type=int, default=1, help="print every n-th row (and the last)")
    parser.add_argument("--expect-residual-below", type=float, metavar="FRACTION",
                        help="fail (exit 1) unless the largest |relative residual| past the first "
                             "tenth of the run is below FRACTION")
    args = parser.parse_args()
    if args.run:
        if not args.out:
            parser.error("--run needs --out")
        run(args.run, args.out, args.set, args.mpile, args.threads)
        path = Path(args.out)
    elif args.path:
        path = Path(args.path)
    else:
        parser.error("give a run's directory or --run")
    history = path / "history.h5" if path.is_dir() else path

    names = ["/time", "/energy/external_work", "/energy/kinetic", "/energy/elastic", "/energy/plastic",
             "/energy/contact", "/energy/transfer", "/energy/damping", "/energy/residual",
             "/energy/relative_residual", f"/bodies/{args.body}/u_y", f"/bodies/{args.body}/v_y",
             f"/bodies/{args.body}/driving_F_y", f"/bodies/{args.body}/contact_F_y",
             f"/reactions/{args.body}/{args.surface}/F_y"]
    s = mpile.read_series(str(history), names)
    with h5py.File(history, "r") as f:
        plan_area = float(f[f"/reactions/{args.body}/{args.surface}"].attrs.get("plan_area", np.nan))
        status = f.attrs.get("status", "")
        if isinstance(status, bytes):
            status = status.decode()
    c, model, case = material_cohesion(history, args.body)
    footing = next((b for b in case.get("bodies", []) if b.get("name") == args.body), {})
    width = 2.0 * max(footing.get("region", {}).get("r", [0.0, np.nan]))  # B = 2 R (2 x half-width)
    t = s["/time"]
    kinetic0 = s["/energy/kinetic"][0]
    elastic0 = s["/energy/elastic"][0]
    internal = s["/energy/elastic"] - elastic0 + s["/energy/plastic"]
    dkin = s["/energy/kinetic"] - kinetic0
    v = s[f"/bodies/{args.body}/v_y"]
    drive = s[f"/bodies/{args.body}/driving_F_y"]
    power = drive * v
    driving_work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    soil_side = internal + dkin + s["/energy/contact"] + s["/energy/transfer"] + s["/energy/damping"]
    q = s[f"/reactions/{args.body}/{args.surface}/F_y"] / plan_area
    print(f"# {history}: status {status!r}; base plan area {plan_area:.6g} m^2 (per radian or metre)")
    if c:
        print(f"# soil {model}, c = {c:g} Pa: circle's limit {CIRCLE_SMOOTH} c = {CIRCLE_SMOOTH * c / 1e3:.1f} kPa "
              f"smooth, {CIRCLE_ROUGH} c = {CIRCLE_ROUGH * c / 1e3:.1f} kPa rough; strip (2+pi) c = "
              f"{(2 + np.pi) * c / 1e3:.1f} kPa")
    header = ("t", "settle", "q_kPa", "q/c", "W_ext", "W_drive", "dKin", "W_int", "contact", "transfer",
              "damping", "soil_side", "residual", "rel_%")
    print(" ".join(f"{h:>9}" for h in header))
    rows = list(range(0, len(t), max(1, args.every)))
    if rows[-1] != len(t) - 1:
        rows.append(len(t) - 1)
    for i in rows:
        values = (t[i], -s[f"/bodies/{args.body}/u_y"][i], q[i] / 1e3, q[i] / c if c else np.nan,
                  s["/energy/external_work"][i], driving_work[i], dkin[i], internal[i], s["/energy/contact"][i],
                  s["/energy/transfer"][i], s["/energy/damping"][i], soil_side[i], s["/energy/residual"][i],
                  100 * s["/energy/relative_residual"][i])
        print(" ".join(f"{x:9.4g}" for x in values))
    # The base pressure's mean over bands of settlement (it swings as the base crosses grid lines).
    settle = -s[f"/bodies/{args.body}/u_y"]
    if c and np.isfinite(width):
        bands = [(0.02, 0.05), (0.05, 0.1), (0.1, 0.15), (0.15, 0.2), (0.05, 0.2)]
        parts = []
        for lo, hi in bands:
            inside = (settle >= lo * width) & (settle <= hi * width)
            if inside.any():
                parts.append(f"{lo:g}-{hi:g} B: {np.mean(q[inside]) / c:.2f}")
        print(f"# mean q / c over settlement bands (B = {width:g} m): " + ", ".join(parts))
    if args.expect_residual_below is not None:
        late = t >= 0.1 * t[-1]  # the first rows' ratio is of tiny energies
        worst = float(np.max(np.abs(s["/energy/relative_residual"][late])))
        ok = status.startswith("complete") and worst < args.expect_residual_below
        print(f"footing ledger: largest |relative residual| {worst:.4f} "
              f"({'ok' if ok else 'FAILED'}, bound {args.expect_residual_below:g})")
        return 0 if ok else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
