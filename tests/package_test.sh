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

# near OUTPUT_FILE X,Y R G B A TOL: the program printed "pixel X,Y = r g b a" within TOL of (R, G, B, A).
near() {
  local output=$1 at=$2 tol=$7
  local got
  got=$(grep "^pixel $at = " "$output" | sed 's/.*= //') || { echo "package_test: no pixel $at in $output" >&2; exit 1; }
  awk -v got="$got" -v want="$3 $4 $5 $6" -v tol="$tol" -v at="$at" 'BEGIN {
    split(got, g, " "); split(want, w, " ");
    for (i = 1; i <= 4; i++) if (g[i] - w[i] > tol || w[i] - g[i] > tol) {
      printf "package_test: pixel %s = %s, want %s (+-%d)\n", at, got, want, tol > "/dev/stderr"; exit 1 } }'
}
# same OUTPUT_FILE X,Y X2,Y2 TOL: the two printed pixels agree within TOL.
same() {
  local a b
  a=$(grep "^pixel $2 = " "$1" | sed 's/.*= //')
  b=$(grep "^pixel $3 = " "$1" | sed 's/.*= //')
  # shellcheck disable=SC2086
  near "$1" "$2" $b "$4" || { echo "package_test: pixels $2 ($a) and $3 ($b) differ" >&2; exit 1; }
}

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
"$work/cmake/poster_c" "$work/poster_c_cmake.png" >"$work/poster_c_cmake.txt"
"$work/cmake/poster_cpp" "$work/poster_cpp.png" >"$work/poster_cpp.txt"

# 2. pkg-config, nothing but the compiler and the flags vraster.pc gives.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
# shellcheck disable=SC2046
c++ -std=c++20 "$src/samples/hello_vraster.cpp" -o "$work/hello_pc" $(pkg-config --cflags --libs vraster)
"$work/hello_pc" "$work/hello_pc.png" >"$work/hello_pc.txt"
expect "$work/hello_pc.txt" "pixel 32,32 = 255 0 0 255" "pixel 2,2 = 255 255 255 255"
# The C poster with a C compiler: C++ runtime, libpng, FreeType, HarfBuzz, fribidi all come from the .pc files.
# shellcheck disable=SC2046
cc -std=c99 "$src/samples/poster.c" -o "$work/poster_pc" $(pkg-config --cflags --libs vraster-text)
"$work/poster_pc" "$work/poster_c_pc.png" >"$work/poster_c_pc.txt"
# SVG text: the SVG library pulls in the text library (vraster-svg.pc requires vraster-text).
if [[ -f $prefix/lib/pkgconfig/vraster-text.pc ]]; then
  cat >"$work/svg_text.cpp" <<'CPP'
#include <cstdio>
#include <variant>
#include "svg_subset/tree.hpp"
int main() {
  const vraster::svg::Tree tree = vraster::svg::parse_svg_tree(
      "<svg xmlns='http://www.w3.org/2000/svg' width='60' height='30'><text x='5' y='20'>Hi</text></svg>");
  const auto& text = std::get<vraster::svg::Group>(tree.root.children.at(0).value);
  std::printf("text paths %zu\n", text.children.size());
}
CPP
  # shellcheck disable=SC2046
  c++ -std=c++20 "$work/svg_text.cpp" -o "$work/svg_text_pc" $(pkg-config --cflags --libs vraster-svg)
  "$work/svg_text_pc" >"$work/svg_text_pc.txt"
  expect "$work/svg_text_pc.txt" "text paths 1"
fi

# 3. The poster's pixels: the sky gradient half way down, the frame's clip hiding the sun beside it, the sun's
#    centre (its first stop, 1 0.95 0.6), and the same picture from every build and from both APIs.
for run in poster_c_cmake poster_c_pc poster_cpp; do
  near "$work/$run.txt" 2,160 55 30 75 255 2
  same "$work/$run.txt" 450,70 2,70 1
  near "$work/$run.txt" 420,70 255 241 152 255 3
done
cmp "$work/poster_c_cmake.png" "$work/poster_c_pc.png"
cmp "$work/poster_c_cmake.png" "$work/poster_cpp.png"
echo "package_test: installed; samples built out of tree with find_package and pkg-config (C and C++); pixels as expected"
