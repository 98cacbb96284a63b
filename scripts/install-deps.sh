#!/usr/bin/env bash
# Installs the Debian packages xshell needs, skipping those already present.
# Run as root on Debian bookworm (or with sudo available).
set -euo pipefail
packages=(
  build-essential cmake pkg-config clang-format
  libeigen3-dev libsundials-dev libsuitesparse-dev libvtk9-dev
  doctest-dev nlohmann-json3-dev libcli11-dev libspectra-dev
  coinor-libipopt-dev
  libopenblas0-openmp
  xvfb xauth fonts-dejavu-core
  clang libclang-rt-14-dev
  python3-matplotlib
  python3-dev pybind11-dev python3-numpy python3-scipy python3-pytest
  python3-distributed python3-dask
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
