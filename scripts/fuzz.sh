#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (address + undefined-behaviour sanitizers) and runs each for a fixed time
# from the committed seed corpus. Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 30)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
seconds=${1:-30}
bash scripts/setup.sh --fuzz
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVRASTER_FUZZ=ON \
  -DVRASTER_SANITIZE=ON -DVRASTER_BUILD_TESTS=OFF -DVRASTER_BUILD_TEXT=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_path_data fuzz_raster fuzz_canvas
for target in path_data raster canvas; do
  work=$(mktemp -d)
  cp -r "tests/fuzz/corpus/$target/." "$work/"
  echo "fuzz_$target: ${seconds}s"
  # Crashes land in build-fuzz/; a crash fails this script (and CI).
  ./build-fuzz/tests/fuzz/fuzz_$target "$work" -max_total_time="$seconds" -max_len=3600 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix=build-fuzz/crash-$target- -print_final_stats=1 2>&1 | tail -n 12
  rm -rf "$work"
done
echo "fuzz: no crashes"
