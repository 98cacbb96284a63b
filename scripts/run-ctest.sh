#!/usr/bin/env bash
# Runs ctest in the current build folder with the given arguments, under a
# virtual X server (xvfb-run) when there is one, so that the rendering tests
# render; then says how many tests CTest reported as skipped (a case that
# cannot run here: missing data, no display, running as root) and which.
# Exits with ctest's status.
set -uo pipefail
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Xvfb runs with -noreset: by default it resets when its last client leaves,
# and a test connecting at that moment fails with "cannot open X display".
if command -v xvfb-run >/dev/null 2>&1; then
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j"$(nproc)" "$@" | tee "$log"
else
  ctest --output-on-failure -j"$(nproc)" "$@" | tee "$log"
fi
status=${PIPESTATUS[0]}
skipped=$(grep -c '(Skipped)$' "$log" || true)
echo "ctest: $skipped tests skipped"
exit "$status"
