#!/usr/bin/env bash
# Builds the libFuzzer targets of the OBJ and configuration readers with clang
# (and ASan/UBSan) into build-fuzz/ and runs each for a bounded time
# (FUZZ_SECONDS, default 60) from the corpora in fuzz/corpus. Any finding
# (crash, sanitizer report, uncaught exception) fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds="${FUZZ_SECONDS:-60}"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DXSHELL_FUZZ=ON \
  -DXSHELL_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_obj_reader fuzz_config_reader
for target in obj_reader:obj config_reader:config; do
  name="${target%%:*}"; corpus="${target##*:}"
  work="build-fuzz/corpus-$corpus"
  mkdir -p "$work"
  echo "fuzzing $name for $seconds s"
  ./build-fuzz/fuzz/fuzz_"$name" -max_total_time="$seconds" -max_len=4096 "$work" "fuzz/corpus/$corpus" \
    -artifact_prefix=build-fuzz/ 2>&1 | tail -n 3
done
