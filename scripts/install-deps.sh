#!/usr/bin/env bash
# Installs the Debian packages xshell needs, skipping those already present.
# Run as root on Debian bookworm (or with sudo available). Never removes a
# package: apt-get runs with --no-remove.
#
# VTK: libvtk9-dev, unless ParaView's Python (python3-paraview, which gives
# pvpython and pvbatch) is installed. python3-paraview conflicts with
# python3-vtk9, on which libvtk9-dev depends; xshell then builds against the
# VTK inside ParaView (paraview-dev, cmake/Vtk.cmake), with the development
# files of the libraries that VTK's CMake package looks for.
set -euo pipefail
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
if installed python3-paraview; then
  vtk=(paraview-dev libdouble-conversion-dev libexpat1-dev libfreetype-dev libgl-dev libopengl-dev libglew-dev
    libjpeg-dev liblz4-dev liblzma-dev libpng-dev libtiff-dev libutfcpp-dev libx11-dev libxt-dev zlib1g-dev)
  echo "install-deps: ParaView's Python is installed: VTK from paraview-dev instead of libvtk9-dev"
else
  vtk=(libvtk9-dev)
fi
packages=(
  build-essential cmake pkg-config clang-format
  libeigen3-dev libsundials-dev libsuitesparse-dev "${vtk[@]}"
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
  installed "$p" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-remove --no-install-recommends "${missing[@]}" >/dev/null
