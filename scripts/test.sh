#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (including
# the tests labelled "validation"). Fails when any test fails. The suite runs
# under a virtual X server (xvfb-run) so that the rendering test renders,
# and says how many tests were skipped (scripts/run-ctest.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
# OpenMP threads wait passively: several test programs run at once.
export OMP_WAIT_POLICY=PASSIVE
cd build
bash ../scripts/run-ctest.sh "$@"
