#!/usr/bin/env bash
# Proves that xshell builds and draws on a machine with ParaView (README,
# "Building on a machine with ParaView"). Not run by CI.
#
#   bash scripts/prove-paraview.sh --yes        installs ParaView, then proves
#   bash scripts/prove-paraview.sh --no-install ParaView is there already
#
# 1. Installs paraview, python3-paraview (pvpython, pvbatch) and paraview-dev.
#    On Debian bookworm python3-paraview conflicts with python3-vtk9: apt
#    REMOVES libvtk9-dev and python3-vtk9, which is why it asks for --yes.
# 2. scripts/install-deps.sh: the rest, with paraview-dev's VTK in place of
#    libvtk9-dev.
# 3. Builds the xshell program against ParaView's VTK in build-paraview/
#    (XSHELL_VTK_FROM_PARAVIEW=ON, cmake/Vtk.cmake).
# 4. Relaxes the bundled sample into out/prove-paraview/.
# 5. Draws its last step with pvpython and scripts/paraview/xshell_view.py
#    (under xvfb-run -a without a display): out/prove-paraview/paraview.png.
#
# With --no-install, CMAKE_PREFIX_PATH may name the prefix of a ParaView that
# is not installed (e.g. unpacked .debs: PREFIX/usr) and XSHELL_PVPYTHON its
# pvpython (or a wrapper setting its library paths).
set -euo pipefail
cd "$(dirname "$0")/.."
install=""
case "${1:-}" in
  --yes) install=1 ;;
  --no-install) ;;
  *)
    echo "usage: $0 --yes | --no-install" >&2
    echo "  --yes installs ParaView's Python, which removes libvtk9-dev and python3-vtk9" >&2
    exit 2 ;;
esac
step() { echo; echo "prove-paraview: $*"; }

if [ -n "$install" ]; then
  step "1. installing paraview python3-paraview paraview-dev (removes libvtk9-dev and python3-vtk9)"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    paraview python3-paraview paraview-dev >/dev/null
  step "2. scripts/install-deps.sh"
  bash scripts/install-deps.sh
fi

step "3. building xshell against ParaView's VTK in build-paraview/"
cmake -S . -B build-paraview -DCMAKE_BUILD_TYPE=Release -DXSHELL_VTK_FROM_PARAVIEW=ON \
  -DXSHELL_BUILD_TESTS=OFF -DXSHELL_PYTHON=OFF | grep "xshell: VTK"
cmake --build build-paraview -j"$(nproc)" --target xshell | tail -n 1

step "4. relaxing the sample into out/prove-paraview/"
./build-paraview/app/xshell relax samples/grid_gravity.json --out out/prove-paraview --quiet

pvpython="${XSHELL_PVPYTHON:-$(command -v pvpython || command -v pvbatch || true)}"
[ -n "$pvpython" ] || { echo "prove-paraview: no pvpython (install python3-paraview)" >&2; exit 2; }
step "5. drawing it with $pvpython scripts/paraview/xshell_view.py"
bash scripts/paraview/run-pvpython.sh "$pvpython" scripts/paraview/xshell_view.py out/prove-paraview \
  --frames d1 d2 --out out/prove-paraview/paraview.png

step "done: xshell built against $(grep -o 'VTK_DIR:PATH=.*' build-paraview/CMakeCache.txt | cut -d= -f2),"
echo "  the sample relaxed into out/prove-paraview/ and drawn by ParaView: out/prove-paraview/paraview.png"
