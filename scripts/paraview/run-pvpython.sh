#!/usr/bin/env bash
# Runs ParaView's Python on a script: run-pvpython.sh PVPYTHON SCRIPT ARGS...
# (PVPYTHON: pvpython or pvbatch), under `xvfb-run -a` when there is no
# DISPLAY. Exit status: the script's; 77 when there is no display and no
# xvfb-run.
#
# Debian's ParaView 5.11 aborts now and then (about one run in four on the
# machine where this was written, more when it is loaded, under xvfb-run and
# a long-running Xvfb alike) when XOpenDisplay fails in
# vtkOpenGLRenderWindow::SupportsOpenGL ("bad X server connection"), as the
# first view is made, before anything is drawn or written. Such a run is
# repeated, up to 6 times; any other failure is the script's status.
set -uo pipefail
pvpython="$1"
shift
display=()
if [ -z "${DISPLAY:-}" ]; then
  command -v xvfb-run >/dev/null || { echo "run-pvpython: no display and no xvfb-run" >&2; exit 77; }
  display=(xvfb-run -a)
fi
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3 4 5 6; do
  "${display[@]}" "$pvpython" "$@" > "$log" 2>&1
  status=$?
  grep -q "bad X server connection" "$log" || break
  echo "run-pvpython: ParaView could not open the display (attempt $attempt)" >&2
done
# ParaView's stack traces are long: the messages only.
grep -v -E '^\s*$|^\s*[0-9]+\s+0x' "$log"
exit $status
