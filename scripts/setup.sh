#!/usr/bin/env bash
# Installs the Debian packages vraster needs (idempotent: installs only what is missing). Run as root.
set -euo pipefail

packages=(
  cmake g++ make pkg-config            # toolchain
  libfreetype-dev libharfbuzz-dev      # fonts and shaping (text/)
  libfribidi-dev                       # bidirectional text (text/)
  libpng-dev                           # PNG output and input
  libjpeg62-turbo-dev libgif-dev       # JPEG and GIF input (SVG <image>)
  libwebp-dev                          # WebP input (SVG <image>)
  zlib1g-dev                           # .svgz images inside SVG
  libfontconfig-dev                    # system fonts for text (text/FontDb)
  libpugixml-dev                       # XML parser (svg_subset/)
  libgtest-dev                         # tests
  libcairo2-dev                        # peer in benchmarks and cross-check tests only
  libharfbuzz-bin                      # hb-view / hb-shape, references for text tests
  # Fonts the text tests use (found at their installed paths, see text/tests/text_support.hpp):
  fonts-noto-core                      # Noto Serif (ligatures), Noto Sans Devanagari
  fonts-hosny-amiri                    # Amiri (Arabic joining)
  fonts-cantarell                      # Cantarell (OpenType with CFF outlines)
  fonts-wqy-microhei                   # WenQuanYi Micro Hei (a .ttc collection of two faces)
  fonts-noto-color-emoji               # Noto Color Emoji (CBDT colour bitmap glyphs)
)

# The fuzz targets need clang and its libFuzzer runtime.
if [[ ${1:-} == --fuzz ]]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
as_root=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: run as root (or install sudo)" >&2; exit 1; }
  as_root=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update
"${as_root[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
