#!/usr/bin/env bash
# Fails when a tracked C++ file differs from .clang-format (Debian's
# clang-format 14), naming every such file. `clang-format -i FILE` fixes one.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null 2>&1 || bash scripts/install-deps.sh
files=$(git ls-files '*.cpp' '*.hpp' '*.h')
bad=()
for f in $files; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
count=$(echo "$files" | wc -w)
if [ ${#bad[@]} -gt 0 ]; then
  echo "check-format: ${#bad[@]} of $count files differ from .clang-format (clang-format -i FILE):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check-format: all $count files follow .clang-format ($(clang-format --version))"
