#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# into build-sanitize/ and runs it; any sanitizer report (memory error,
# undefined behaviour, leak) aborts the process it happens in, in a test
# program or in an xshell program that a command test runs, and so fails a
# test. Extra arguments go to ctest (CI passes -LE validation).
#
# Third-party leaks: scripts/lsan.supp names the libraries whose one-time
# allocations are never freed. Mesa's software GL driver (swrast_dri.so) is
# loaded and unloaded by every render window, and what it leaks is reported
# with no module name to suppress; the tests that render ("needs a display")
# therefore run with the driver preloaded, so that it stays loaded and its
# memory stays reachable.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The Python module is not built here: an extension instrumented with ASan
# cannot load into an uninstrumented python3 (its tests, labelled "python",
# run in the Release build of scripts/test.sh).
#
# -O1 with line tables only (-g1): the instrumented build of the Hessian's
# template-heavy kernels takes less than half the time it takes at -O2 -g,
# and reports still name file and line.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DXSHELL_SANITIZE=ON -DXSHELL_PYTHON=OFF >/dev/null
cmake --build build-sanitize -j"$(nproc)"
asan=halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1
export ASAN_OPTIONS="$asan"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1
# OpenMP threads wait passively: several test programs run at once.
export OMP_WAIT_POLICY=PASSIVE
cd build-sanitize
run_ctest() { bash ../scripts/run-ctest.sh "$@"; }
run_ctest -E "needs a display" "$@"
driver=$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null | head -n 1 || true)
if [ -n "$driver" ]; then
  LD_PRELOAD="$driver" ASAN_OPTIONS="$asan:verify_asan_link_order=0" run_ctest -R "needs a display" "$@"
else
  run_ctest -R "needs a display" "$@"
fi
