"""The soil beside a shaft in bands: the mean radial effective stress, void ratio and excess pore
pressure of the particles in each band of depth and distance from the wall, in every particle
snapshot of a run.

    import mpile
    bands = mpile.shaft_bands("out/gdp_cycles_quick", wall=0.373, surface=10.0,
                              depths=[(0.5, 1.5), (1.5, 2.5)], distances=[0.0, 0.05, 0.1, 0.2])
    bands["sigma_r"].sel(distance=0.025)           # the band next to the wall, against time
    bands["sigma_r"] / bands["sigma_r"].isel(time=0)  # what the cycles have done to it

A band is fixed in space (the particles in it at each snapshot): depth = surface - y in
[top, bottom), distance = r - wall in [inner, outer). Single points beside a wall scatter as the
particles pass them; a band's mean over some tens of particles does not. Only soil counts: the
particles of rigid bodies (material names ending in "(rigid)") and those inside the wall's radius
are left out.

Signs as a geotechnical engineer reads them: sigma_r is the radial effective stress, compression
positive, -(sigma_rr - p_w) with p_w the pore pressure (tension positive) where the snapshot has
one; excess_pore_pressure is compression positive (the snapshots' is tension positive). The void
ratio is the material state's (hypoplastic sand); NaN where the soil has none.
"""
import numpy as np

from .files import RunFileError


def _band_means(positions, arrays, rigid, wall, surface, depths, distances):
    """{quantity: (depths, bands) array of means} and the particle counts, for one snapshot."""
    depth = surface - positions[:, 1]
    distance = positions[:, 0] - wall
    soil = ~rigid & (distance >= 0.0)
    pore = arrays.get("pore_pressure")
    sigma_r = -(arrays["sigma_rr"] - (pore if pore is not None else 0.0))
    quantities = {
        "sigma_r": sigma_r,
        "void_ratio": arrays.get("void_ratio"),
        "excess_pore_pressure": -arrays["excess_pore_pressure"] if "excess_pore_pressure" in arrays else None,
    }
    shape = (len(depths), len(distances) - 1)
    means = {name: np.full(shape, np.nan) for name in quantities}
    count = np.zeros(shape, dtype=np.int64)
    for i, (top, bottom) in enumerate(depths):
        in_depth = soil & (depth >= top) & (depth < bottom)
        for j in range(len(distances) - 1):
            inside = in_depth & (distance >= distances[j]) & (distance < distances[j + 1])
            count[i, j] = int(inside.sum())
            if count[i, j] == 0:
                continue
            for name, values in quantities.items():
                if values is not None:
                    means[name][i, j] = float(values[inside].mean())
    return means, count


def shaft_bands(path, wall, surface, depths, distances, snapshots=None):
    """An xarray Dataset on (time, depth, distance): sigma_r (Pa), void_ratio, excess_pore_pressure
    (Pa) and count (particles) per band, for each particle snapshot of the run at `path` (or the
    `snapshots` given). `depth` is each band's mid-depth, `distance` its mid-distance from the wall;
    the bands' edges are the attributes depth_bands and distance_edges.

    `wall`: the wall's radius (m); `surface`: the ground's y (m); `depths`: (top, bottom) pairs of
    depth below the surface (m); `distances`: increasing edges of distance from the wall (m).
    Refuses bands that are empty or out of order, naming them."""
    import xarray as xr

    from .snapshots import open_snapshots, rigid_particles

    depths = [(float(top), float(bottom)) for top, bottom in depths]
    distances = [float(d) for d in distances]
    for top, bottom in depths:
        if not bottom > top:
            raise ValueError(f"a depth band must go down: ({top}, {bottom})")
    if len(distances) < 2 or any(not b > a for a, b in zip(distances, distances[1:])):
        raise ValueError(f"distances must be at least two increasing edges, got {distances}")
    snapshots = open_snapshots(path) if snapshots is None else snapshots
    if len(snapshots) == 0:
        raise RunFileError(f"{path}: no particle snapshot")
    series = {name: [] for name in ("sigma_r", "void_ratio", "excess_pore_pressure")}
    counts, times = [], []
    for snapshot in snapshots:
        arrays = snapshot.arrays
        means, count = _band_means(snapshot.positions, arrays, rigid_particles(snapshot), wall, surface,
                                   depths, distances)
        for name, values in series.items():
            values.append(means[name])
        counts.append(count)
        times.append(snapshot.time)
    coords = {"time": np.array(times),
              "depth": [0.5 * (top + bottom) for top, bottom in depths],
              "distance": [0.5 * (a + b) for a, b in zip(distances, distances[1:])]}
    dims = ("time", "depth", "distance")
    data = {name: (dims, np.array(values)) for name, values in series.items()}
    data["count"] = (dims, np.array(counts))
    bands = xr.Dataset(data, coords=coords,
                       attrs={"wall": wall, "surface": surface,
                              "depth_bands": np.array(depths).ravel(),
                              "distance_edges": np.array(distances)})
    bands["sigma_r"].attrs["units"] = "Pa"
    bands["excess_pore_pressure"].attrs["units"] = "Pa"
    return bands
