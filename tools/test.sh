#!/usr/bin/env bash
# Builds and runs the test suite in three configurations: optimised (release), AddressSanitizer +
# UndefinedBehaviorSanitizer (asan) and ThreadSanitizer (tsan). Choose configurations by naming
# them: `bash tools/test.sh release`. Installs missing Debian packages first.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
presets=("$@")
if [ ${#presets[@]} -eq 0 ]; then
  presets=(release asan tsan)
fi
jobs=$(nproc)
for preset in "${presets[@]}"; do
  echo "== $preset: configure and build"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  echo "== $preset: tests"
  ctest --preset "$preset" -j "$jobs"
done
