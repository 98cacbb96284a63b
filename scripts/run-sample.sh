#!/usr/bin/env bash
# Installs what is missing, builds the xshell program (only what the sample
# needs: scripts/test.sh builds the rest), and relaxes the bundled sample
# linkage under gravity with Newton; outputs (summary.json, state.json,
# series.pvd and .vtp files) go to out/grid_gravity/.
set -euo pipefail
cd "$(dirname "$0")/.."
XSHELL_BUILD_TARGETS=xshell bash scripts/build.sh
./build/app/xshell relax samples/grid_gravity.json "$@"
