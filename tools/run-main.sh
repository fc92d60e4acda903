#!/usr/bin/env bash
# The main job: installs missing Debian packages, builds mpile (release), runs the quick GDP
# monopile case (the seed paper's torsional installation, cases/monopile/gdp_quick.toml), then
# draws the seed's figures 3 to 7 and the sigma_ry field from its outputs. Extra arguments go to
# `mpile run` (for example --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target mpile
out=out/gdp_quick
build/release/bin/mpile run cases/monopile/gdp_quick.toml --out "$out" "$@"
/usr/bin/python3 tools/plot_monopile.py "$out" --out "$out/figures" --table 0.05,0.1
# Body 3 is the pile (bodies in the order [monopile] builds them); it is drawn grey, outlined,
# with its tip's depth marked.
/usr/bin/python3 tools/render_sigma_ry.py "$out/particles.pvd" --last \
  --out "$out/figures/sigma_ry.png" --window 0 1.5 5.5 10.5 --pile-body 3 \
  --title "GDP quick: sigma_ry at the last snapshot"
cat <<MESSAGE

Done. Figures (the seed's figures 3 to 7 and the sigma_ry field): $out/figures/
Force histories (HDF5): $out/history.h5
ParaView: open $out/particles.pvd, colour by sigma_ry (range about -50 to 50 kPa, a diverging
map such as "Cool to Warm"), and use the time controls to step through the snapshots.
MESSAGE
