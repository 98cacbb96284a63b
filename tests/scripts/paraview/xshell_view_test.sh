#!/usr/bin/env bash
# Test of scripts/paraview/xshell_view.py (tests/scripts/paraview/CMakeLists.txt
# runs it): the xshell program relaxes the bundled sample into WORK/run, the
# script draws its last step (a PNG) and the whole series (a PNG per step),
# check_png.py checks the pictures; an unknown array is exit status 2 with the
# list of arrays. Skipped (exit 77) without pvpython/pvbatch, or without a
# display and xvfb-run.
#
# Environment: XSHELL_PROGRAM, XSHELL_SAMPLES_DIR, XSHELL_PVPYTHON (pvpython or
# pvbatch; empty: looked up in PATH), WORK (a scratch folder).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
script="$here/../../../scripts/paraview/xshell_view.py"
pvpython="${XSHELL_PVPYTHON:-}"
[ -n "$pvpython" ] || pvpython="$(command -v pvpython || command -v pvbatch || true)"
if [ -z "$pvpython" ] || [ ! -x "$pvpython" ]; then
  echo "skipped: no pvpython or pvbatch (set XSHELL_PVPYTHON or put one in PATH)"
  exit 77
fi
fail() { echo "FAILED: $*"; exit 1; }

# The script, by run-pvpython.sh (a display, and the repeat of a run that
# could not open it); its output in $WORK/view.log.
view() {
  bash "$here/../../../scripts/paraview/run-pvpython.sh" "$pvpython" "$script" "$@" > "$WORK/view.log" 2>&1
  local status=$?
  tail -n 5 "$WORK/view.log"
  [ "$status" -ne 77 ] || { echo "skipped: no display and no xvfb-run"; exit 77; }
  return $status
}

rm -rf "$WORK" && mkdir -p "$WORK" || fail "cannot make $WORK"
"$XSHELL_PROGRAM" relax "$XSHELL_SAMPLES_DIR/grid_gravity.json" --out "$WORK/run" --quiet ||
  fail "xshell relax on the sample"
steps=$(grep -c 'part="0"' "$WORK/run/series.pvd")
echo "the sample's series: $steps steps"

view "$WORK/run" --color curvature --frames d1 d2 --out "$WORK/last.png" --width 640 --height 480 ||
  fail "xshell_view.py on the last step (status $?)"
"$pvpython" "$here/check_png.py" "$WORK/last.png" 640 480 || fail "the picture of the last step"

view "$WORK/run" --animation "$WORK/anim.png" --width 320 --height 240 || fail "xshell_view.py --animation"
count=$(find "$WORK" -maxdepth 1 -name 'anim.*.png' | wc -l)
echo "animation: $count pictures"
[ "$count" -eq "$steps" ] || fail "$count pictures for $steps steps"
"$pvpython" "$here/check_png.py" "$(find "$WORK" -maxdepth 1 -name 'anim.*.png' | sort | head -n 1)" 320 240 ||
  fail "the animation's first picture"

view "$WORK/run" --color no_such_array --out "$WORK/none.png"
status=$?
[ "$status" -eq 2 ] || fail "an unknown array: status $status, expected 2"
grep -q "arrays: .*bending_density" "$WORK/view.log" || fail "an unknown array: the message lists no arrays"
[ ! -e "$WORK/none.png" ] || fail "an unknown array wrote a picture"
echo "passed"
