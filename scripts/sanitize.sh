#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# into build-sanitize/ and runs it; any sanitizer report (memory error,
# undefined behaviour, leak) aborts the process it happens in, in a test
# program or in the xshell program a command test runs, and so fails a test.
# Leaks inside third-party libraries only (scripts/lsan.supp) are ignored.
# Extra arguments go to ctest (CI passes -LE validation).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DXSHELL_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1
# OpenMP threads wait passively: several test programs run at once.
export OMP_WAIT_POLICY=PASSIVE
cd build-sanitize
if command -v xvfb-run >/dev/null 2>&1; then
  xvfb-run -a ctest --output-on-failure -j"$(nproc)" "$@"
else
  ctest --output-on-failure -j"$(nproc)" "$@"
fi
