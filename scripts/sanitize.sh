#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# into build-sanitize/ and runs it; any sanitizer report fails a test.
# Extra arguments go to ctest (e.g. -LE validation).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DXSHELL_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# OpenMP threads wait passively: several test programs run at once.
export OMP_WAIT_POLICY=PASSIVE
cd build-sanitize
if command -v xvfb-run >/dev/null 2>&1; then
  xvfb-run -a ctest --output-on-failure -j"$(nproc)" "$@"
else
  ctest --output-on-failure -j"$(nproc)" "$@"
fi
