#!/usr/bin/env bash
# Installs what is missing, then configures and builds xshell into build/.
# Extra arguments go to CMake's configure step. XSHELL_BUILD_TARGETS (a
# space-separated list) builds only those targets; by default, everything
# (the program, the test suite, the benchmark).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${XSHELL_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
