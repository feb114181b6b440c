#!/usr/bin/env bash
# Builds everything with address + undefined-behaviour sanitizers (Debug) and runs every test through CTest.
# The benchmark programs are built too (not run): they must keep compiling, and this way CI needs no extra build.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
bash scripts/setup.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DVRASTER_SANITIZE=ON -DVRASTER_BUILD_BENCH=ON >/dev/null
cmake --build build-asan -j"$(nproc)"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)"
