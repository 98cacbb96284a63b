#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (including
# the tests labelled "validation"). Fails when any test fails. The suite runs
# under a virtual X server (xvfb-run) so that the rendering test renders.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
# OpenMP threads wait passively: several test programs run at once.
# Xvfb runs with -noreset: by default it resets when its last client leaves,
# and a test connecting at that moment fails with "cannot open X display".
export OMP_WAIT_POLICY=PASSIVE
cd build
if command -v xvfb-run >/dev/null 2>&1; then
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j"$(nproc)" "$@"
else
  ctest --output-on-failure -j"$(nproc)" "$@"
fi
