#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (including
# the tests labelled "validation"). Fails when any test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
