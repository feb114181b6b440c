#!/usr/bin/env bash
# The issue's exactness targets, measured so that background load matters less than in a single median: analytic
# and exact renders of each scene alternate for ROUNDS rounds (default 6) of `vraster render --bench 9`, and each
# mode keeps its best median. Prints exact/analytic against the target.
# Usage: scripts/exactness_targets.sh [ROUNDS]   (needs a built ./build/vraster)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
rounds=${1:-6}
vraster=./build/vraster
[ -x "$vraster" ] || { echo "exactness_targets.sh: build first (scripts/run.sh test or cmake --build build)" >&2; exit 1; }
median() {  # scene, mode -> median ms of 9 frames
  "$vraster" render "$1" --bench 9 --background white --aa "$2" | sed -E 's/.*ms_per_frame_median=([0-9.]+).*/\1/'
}
echo "| scene | analytic ms | exact ms | exact/analytic | target |"
echo "| --- | ---: | ---: | ---: | ---: |"
scenes=../shared/bench/scenes
for entry in tiny_many:1.5 text_outlines:1.5 thin_slivers:1.5 star_big:4 star_big_nz:4; do
  scene=${entry%%:*} target=${entry##*:}
  best_a=inf best_e=inf
  for _ in $(seq "$rounds"); do
    best_a=$(awk -v b="$best_a" -v x="$(median "$scenes/$scene.svg" analytic)" 'BEGIN { print (b == "inf" || x < b) ? x : b }')
    best_e=$(awk -v b="$best_e" -v x="$(median "$scenes/$scene.svg" exact)" 'BEGIN { print (b == "inf" || x < b) ? x : b }')
  done
  awk -v n="$scene" -v a="$best_a" -v e="$best_e" -v t="$target" \
    'BEGIN { printf "| %s | %.2f | %.2f | %.2f | %sx: %s |\n", n, a, e, e / a, t, (e / a <= t) ? "met" : "NOT met" }'
done
