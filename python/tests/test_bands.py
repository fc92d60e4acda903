"""Band means beside a shaft (mpile.shaft_bands) on particles whose values are linear in depth and
distance from the wall: on a regular lattice a band's mean is the value at the band's mid-point,
so every mean is known exactly."""
from dataclasses import dataclass, field

import numpy as np
import pytest

import mpile

WALL = 0.373
SURFACE = 10.0
SPACING = 0.01


@dataclass
class FakeSnapshot:
    """What shaft_bands reads of a snapshot: time, positions, arrays and material names."""

    time: float
    positions: np.ndarray
    arrays: dict = field(default_factory=dict)
    material_names: list = field(default_factory=lambda: ["sand", "pile (rigid)"])


def lattice_snapshot(time, scale):
    # Soil particles at the centres of a 0.01 m lattice from the wall out to 0.8 m and from the
    # surface down to 3 m; a rigid pile's particles inside the wall and, to be ignored, a few
    # in the soil's bands with absurd stresses.
    distance = SPACING * (0.5 + np.arange(80))
    depth = SPACING * (0.5 + np.arange(300))
    d, z = (a.ravel() for a in np.meshgrid(distance, depth))
    r = np.concatenate([WALL + d, np.full(5, WALL - 0.005), WALL + d[:5]])
    y = np.concatenate([SURFACE - z, SURFACE - z[:5], SURFACE - z[:5]])
    depth_all = SURFACE - y
    distance_all = r - WALL
    material = np.concatenate([np.zeros(d.size, dtype=np.int32), np.ones(10, dtype=np.int32)])
    effective = scale * (1e4 * depth_all + 2e4 * distance_all)  # sigma'_r, compression positive
    pore = -5e3 * np.ones_like(r)                                 # tension positive
    sigma_rr = np.where(material == 1, 1e12, -effective + pore)  # total, tension positive
    arrays = {"sigma_rr": sigma_rr, "pore_pressure": pore,
              "excess_pore_pressure": -scale * 2e3 * depth_all,
              "void_ratio": 0.6 + 0.1 * distance_all, "material": material}
    return FakeSnapshot(time, np.column_stack([r, y]), arrays)


def test_band_means_are_the_values_at_the_bands_mid_points():
    snapshots = [lattice_snapshot(0.0, 1.0), lattice_snapshot(0.5, 0.5)]
    bands = mpile.shaft_bands(None, wall=WALL, surface=SURFACE, depths=[(1.0, 2.0), (2.0, 3.0)],
                              distances=[0.0, 0.05, 0.2], snapshots=snapshots)
    assert list(bands["depth"].values) == [1.5, 2.5]
    assert list(bands["distance"].values) == pytest.approx([0.025, 0.125])
    # Particles per band: 100 rows of depth by 5 and 15 columns of distance; the rigid ones left out.
    assert bands["count"].isel(time=0).values.tolist() == [[500, 1500], [500, 1500]]
    for t, scale in enumerate((1.0, 0.5)):
        for i, depth in enumerate((1.5, 2.5)):
            for j, distance in enumerate((0.025, 0.125)):
                point = {"time": t, "depth": i, "distance": j}
                # Means of linear functions over a symmetric lattice: exact to rounding (1e-9).
                assert float(bands["sigma_r"].isel(point)) == pytest.approx(
                    scale * (1e4 * depth + 2e4 * distance), rel=1e-9)
                assert float(bands["excess_pore_pressure"].isel(point)) == pytest.approx(
                    scale * 2e3 * depth, rel=1e-9)
                assert float(bands["void_ratio"].isel(point)) == pytest.approx(
                    0.6 + 0.1 * distance, rel=1e-9)


def test_a_dry_run_without_void_ratio_reads_nan_and_its_effective_stress_is_the_total():
    snapshot = lattice_snapshot(0.0, 1.0)
    for name in ("pore_pressure", "excess_pore_pressure", "void_ratio"):
        del snapshot.arrays[name]
    snapshot.arrays["sigma_rr"] = -1e4 * np.ones(len(snapshot.positions))
    bands = mpile.shaft_bands(None, wall=WALL, surface=SURFACE, depths=[(1.0, 2.0)],
                              distances=[0.0, 0.05], snapshots=[snapshot])
    assert float(bands["sigma_r"].squeeze()) == pytest.approx(1e4)
    assert np.isnan(float(bands["void_ratio"].squeeze()))
    assert np.isnan(float(bands["excess_pore_pressure"].squeeze()))


def test_bands_out_of_order_are_refused():
    snapshots = [lattice_snapshot(0.0, 1.0)]
    with pytest.raises(ValueError, match="depth band must go down"):
        mpile.shaft_bands(None, WALL, SURFACE, [(2.0, 1.0)], [0.0, 0.05], snapshots=snapshots)
    with pytest.raises(ValueError, match="increasing edges"):
        mpile.shaft_bands(None, WALL, SURFACE, [(1.0, 2.0)], [0.05, 0.0], snapshots=snapshots)
