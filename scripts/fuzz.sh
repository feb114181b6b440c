#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (address + undefined-behaviour sanitizers) and runs each for a fixed time
# from its committed seed corpus (tests/fuzz/corpus/<target>/). Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
# (default 30 s each, every target). A crash, a leak, a timeout (10 s for one input) or running out of memory fails
# the script; the input that did it is kept as build-fuzz/crash-<target>-* (turn it into a named test).
# The random seed is fixed (VRASTER_FUZZ_SEED, default 1) so that CI replays the same mutations that were fuzzed
# before a change landed, instead of failing at random on an old bug; VRASTER_FUZZ_SEED=0 picks a new seed each
# run (use it, with longer times, to look for new bugs).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
seconds=${1:-30}
seed=${VRASTER_FUZZ_SEED:-1}
shift || true
bash scripts/setup.sh --fuzz

# target:max_len (each target also refuses longer inputs itself)
all=(path_data:4096 raster:3603 svg:16384 stroke:2716 png:65536 text:65536 mesh:3600 canvas:3600)
if (($# > 0)); then
  wanted=()
  for name in "$@"; do
    found=
    for t in "${all[@]}"; do [[ ${t%%:*} == "$name" ]] && wanted+=("$t") && found=1; done
    [[ -n $found ]] || { echo "fuzz.sh: no target '$name' (targets: ${all[*]%%:*})" >&2; exit 2; }
  done
else
  wanted=("${all[@]}")
fi

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVRASTER_FUZZ=ON \
  -DVRASTER_SANITIZE=ON -DVRASTER_BUILD_TESTS=OFF -DVRASTER_BUILD_TEXT=ON >/dev/null
targets=()
for t in "${wanted[@]}"; do targets+=("fuzz_${t%%:*}"); done
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}" >build-fuzz/build.log 2>&1 ||
  { tail -n 40 build-fuzz/build.log; echo "fuzz.sh: the fuzz targets did not build" >&2; exit 1; }

# Seeds for the text target that cannot be committed (third-party fonts): small subsets of the repository's font
# and of installed Debian fonts (TrueType, CFF, Arabic, Devanagari), made now with hb-subset. Two option bytes
# (size/hinting/text, face index) come first, as the target reads them.
text_seeds() {
  local dir=$1 n=0
  local fonts=(
    "text/fonts/NotoSans-Regular.ttf|Hamburg AVAWA office fluffy 0123"
    "/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf|Hamburg AVAWA office"
    "/usr/share/fonts/opentype/fonts-hosny-amiri/Amiri-Regular.ttf|مرحبا بالعالم abc"
    "/usr/share/fonts/truetype/noto/NotoSansDevanagari-Regular.ttf|नमस्ते"
  )
  for entry in "${fonts[@]}"; do
    local font=${entry%%|*} text=${entry#*|}
    [[ -f $font ]] || { echo "fuzz.sh: seed font $font is missing (bash scripts/setup.sh installs it)" >&2; exit 1; }
    local sub
    sub=$(mktemp)
    hb-subset --output-file="$sub" --text="$text" "$font"
    for options in 00 0d 16 1f; do  # sizes, hinting on and off, the four texts
      { printf "\\x$options\\x00"; cat "$sub"; } >"$dir/subset_${n}_$options"
    done
    rm -f "$sub"
    n=$((n + 1))
  done
}

total=0
for t in "${wanted[@]}"; do
  target=${t%%:*} max_len=${t#*:}
  work=$(mktemp -d)
  cp -r "tests/fuzz/corpus/$target/." "$work/"
  if [[ $target == text ]]; then text_seeds "$work"; fi
  echo "fuzz_$target: ${seconds}s, $(find "$work" -type f | wc -l) seeds, inputs up to $max_len bytes, seed $seed"
  status=0
  ./build-fuzz/tests/fuzz/fuzz_$target "$work" -max_total_time="$seconds" -max_len="$max_len" -timeout=10 -seed="$seed" \
    -rss_limit_mb=2048 -artifact_prefix="build-fuzz/crash-$target-" -print_final_stats=1 >"$work.log" 2>&1 ||
    status=$?
  grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+[[:space:]]+DONE)' "$work.log" | tr '\n' ' '
  echo
  if ((status != 0)); then
    tail -n 40 "$work.log"
    echo "fuzz_$target: FAILED (status $status); the input is in build-fuzz/crash-$target-*" >&2
    rm -rf "$work" "$work.log"
    exit 1
  fi
  rm -rf "$work" "$work.log"
  total=$((total + seconds))
done
echo "fuzz: no crashes (${#wanted[@]} targets, ${total}s of fuzzing)"
