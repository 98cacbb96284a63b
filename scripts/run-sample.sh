#!/usr/bin/env bash
# Installs what is missing, builds, and relaxes the bundled sample linkage
# under gravity with Newton; outputs (summary.json, state.json, series.pvd
# and .vtp files) go to out/grid_gravity/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/app/xshell relax samples/grid_gravity.json "$@"
