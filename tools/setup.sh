#!/usr/bin/env bash
# Installs the Debian packages mpile needs to build, test and post-process.
# Idempotent: installs only what is missing, so it is quick on a machine that has them.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libtbb-dev libhdf5-dev libvtk9-dev
  libgtest-dev libgmock-dev
  libcli11-dev libtoml11-dev
  python3-numpy python3-h5py python3-matplotlib python3-vtk9
  python3-pandas python3-xarray python3-h5netcdf python3-pytest python3-venv python3-setuptools python3-pip
  python3-jsonschema python3-scipy python3-mpmath
  snakemake slurm-wlm munge
  clang-format
  xvfb xauth
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
