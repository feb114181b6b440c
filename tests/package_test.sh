#!/usr/bin/env bash
# Packaging test: installs the build into a temporary prefix, then builds the samples OUT OF TREE against it both
# ways (CMake's find_package(vraster) and pkg-config with a plain compiler line) and checks the pixels they print.
#   tests/package_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null

# expect OUTPUT_FILE LINE...: every LINE must appear in the program's output.
expect() {
  local output=$1
  shift
  for line in "$@"; do
    grep -qxF "$line" "$output" || { echo "package_test: '$line' missing from:" >&2; cat "$output" >&2; exit 1; }
  done
}

# 1. CMake: find_package(vraster) from the installed package.
cmake -S "$src/samples" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/cmake" >/dev/null
"$work/cmake/hello_vraster" "$work/hello_cmake.png" >"$work/hello_cmake.txt"
expect "$work/hello_cmake.txt" "pixel 32,32 = 255 0 0 255" "pixel 2,2 = 255 255 255 255"
test -s "$work/hello_cmake.png"

# 2. pkg-config, nothing but the compiler and the flags vraster.pc gives.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
# shellcheck disable=SC2046
c++ -std=c++20 "$src/samples/hello_vraster.cpp" -o "$work/hello_pc" $(pkg-config --cflags --libs vraster)
"$work/hello_pc" "$work/hello_pc.png" >"$work/hello_pc.txt"
expect "$work/hello_pc.txt" "pixel 32,32 = 255 0 0 255" "pixel 2,2 = 255 255 255 255"
echo "package_test: installed, built out of tree with find_package and pkg-config, pixels as expected"
