#!/usr/bin/env bash
# Builds the benchmark in Release and runs it on the shared scenes: vraster against Cairo and FreeType's smooth
# rasterizer, single-threaded, in the same run. The Markdown table goes to stdout; build output and progress go
# to stderr. Extra arguments go to vraster_bench (e.g. --scene poly10_64 --check --out /tmp/frames; --generated
# renders the benchmark's own generated scenes instead of the shared ones).
#
# Needs what scripts/setup.sh installs (a C++20 compiler, CMake, pkg-config, libpng, pugixml, libcairo2-dev,
# libfreetype-dev); installs nothing itself.
#
# Environment: VRASTER_BENCH_BUILD (build folder, default <repo>/build-bench),
#              VRASTER_BENCH_SCENES (scene folder, default <repo>/../shared/bench/scenes),
#              VRASTER_BENCH_CMAKE_ARGS (extra configure arguments, e.g. -DVRASTER_NATIVE=ON),
#              VRASTER_BENCH_BLEND2D_ROOT (install prefix of a Blend2D build: adds Blend2D to the comparison; Blend2D
#              is not a Debian package, so build it outside this repository yourself).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VRASTER_BENCH_BUILD:-$repo/build-bench}"
scenes="${VRASTER_BENCH_SCENES:-$repo/../shared/bench/scenes}"

for tool in cmake pkg-config; do
  command -v "$tool" >/dev/null || { echo "bench.sh: $tool not found (run scripts/setup.sh)" >&2; exit 1; }
done
for module in cairo freetype2; do
  pkg-config --exists "$module" || { echo "bench.sh: pkg-config cannot find $module (run scripts/setup.sh)" >&2; exit 1; }
done
generated=false
for arg in "$@"; do [ "$arg" = --generated ] && generated=true; done
$generated || [ -d "$scenes" ] || { echo "bench.sh: no scene folder at $scenes" >&2; exit 1; }

# shellcheck disable=SC2086  # VRASTER_BENCH_CMAKE_ARGS is a list of words
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVRASTER_BUILD_BENCH=ON -DVRASTER_BUILD_TESTS=OFF \
  ${VRASTER_BENCH_BLEND2D_ROOT:+-DVRASTER_BENCH_BLEND2D_ROOT="$VRASTER_BENCH_BLEND2D_ROOT"} \
  ${VRASTER_BENCH_CMAKE_ARGS:-} >&2
cmake --build "$build" -j2 --target vraster_bench >&2

if $generated; then
  exec "$build/bench/vraster_bench" "$@"
fi
exec "$build/bench/vraster_bench" "$scenes" "$@"
