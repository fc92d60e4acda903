#!/usr/bin/env bash
# The main job: installs missing Debian packages, builds mpile (release) and runs the default case.
# Until the monopile cases exist, the default case is the shaft-torsion verification (V6): the
# rotational (theta) degree of freedom against its closed form, at twice the test resolution.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target mpile
build/release/bin/mpile verify V6 --refinement 2 "$@"
