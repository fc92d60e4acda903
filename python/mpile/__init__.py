"""Read the outputs of mpile runs (the Material Point Method engine of monopile installation), and
build, run and sweep cases.

    import mpile
    ds = mpile.open_history("out/jacked_quick")          # xarray Dataset on time
    df = mpile.open_history("out/jacked_quick", form="pandas")
    mpile.phases("out/jacked_quick")                      # name, start, end, ended
    snaps = mpile.open_snapshots("out/jacked_quick")      # particles.pvd
    mpile.follow_particle(snaps, 1234)                    # one particle through time
    mpile.open_grid_snapshots("out/run")[-1].contact_profile("pile/tip")  # traction along a surface
    run = mpile.installation("out/jacked_quick")          # the seed's figures 3 to 7
    mpile.radiation("out/gdp_quick")                      # radiated energy, peak particle velocity
    mpile.load_test("out/gdp_quick_capacity")             # load-settlement curve, capacity
    mpile.load_test_zone("out/gdp_quick_capacity", 0.1)   # the sand the load test moved
    mpile.friction_fatigue("out/gdp_cycles_quick", 60.0)  # sigma'_r / sigma'_r0 against cycles
    mpile.shaft_bands("out/cycles", 0.373, 10.0, [(1, 2)], [0, 0.05, 0.1])  # bands beside a shaft

Cases are built and run from Python with the command line's checks (the mpile program does them):

    case = mpile.Case.read("cases/monopile/jacked_quick.toml")
    case["monopile.friction"] = 0.3                       # --set monopile.friction=0.3, checked now
    run = case.run("out/friction_03", threads=2)          # mpile run; run.history(), run.installation()
    case.write("friction_03.toml")                         # a case file of this case
    study = mpile.run_sweep([...cases...], "out/sweeps/friction", gather=[...])  # mpile sweep

The names are imported on first use, so that `import mpile` is quick and the snapshot and display
modules work where only numpy and VTK are (ParaView's Python). The reference is docs/python.md.
"""
import importlib

__version__ = "0.1.0"

_EXPORTS = {
    "open_history": "history",
    "list_datasets": "history",
    "read_series": "history",
    "attributes": "history",
    "case": "history",
    "phases": "phase_table",
    "open_snapshots": "snapshots",
    "follow_particle": "snapshots",
    "open_grid_snapshots": "grid",
    "Snapshot": "snapshots",
    "Snapshots": "snapshots",
    "open_sweep": "sweep",
    "installation": "monopile",
    "Installation": "monopile",
    "InstallationRow": "monopile",
    "shaft_ratios": "monopile",
    "radiation": "vibration",
    "load_test": "capacity",
    "write_load_test_csv": "capacity",
    "friction_fatigue": "fatigue",
    "shaft_bands": "bands",
    "LoadTest": "capacity",
    "load_test_zone": "capacity",
    "LoadTestZone": "capacity",
    "installation_reach": "capacity",
    "InstallationReach": "capacity",
    "run_record": "capacity",
    "wall_tip_fills": "capacity",
    "WallTipFill": "capacity",
    "RunRecord": "capacity",
    "Radiation": "vibration",
    "RunFileError": "files",
    "Case": "cases",
    "CaseError": "cases",
    "CaseWarning": "cases",
    "RunError": "cases",
    "Run": "cases",
    "run_sweep": "cases",
    "SweepRun": "cases",
    "find_mpile": "cases",
    "MpileNotFoundError": "cases",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'mpile' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
