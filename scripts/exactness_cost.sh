#!/usr/bin/env bash
# What exactness costs: median ms per frame of `vraster render --bench` for analytic vs exact coverage and
# non-zero vs non-exterior, on the shared benchmark scenes and the self-intersecting samples.
# Usage: scripts/exactness_cost.sh [FRAMES]   (default 5; needs a built ./build/vraster)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
frames=${1:-5}
vraster=./build/vraster
[ -x "$vraster" ] || { echo "exactness_cost.sh: build first (scripts/run.sh test or cmake --build build)" >&2; exit 1; }
ms() {  # scene, extra args -> median ms
  "$vraster" render "$1" --bench "$frames" --background white "${@:2}" | sed -E 's/.*ms_per_frame_median=([0-9.]+).*/\1/'
}
echo "| scene | analytic ms | exact ms | exact/analytic | nonzero ms (analytic) | nonexterior ms (analytic) | nonexterior/nonzero |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for scene in ../shared/bench/scenes/*.svg samples/pentagram.svg samples/spiral.svg samples/glyph_overlap.svg; do
  a=$(ms "$scene" --aa analytic); e=$(ms "$scene" --aa exact)
  nz=$(ms "$scene" --aa analytic --rule nonzero); ne=$(ms "$scene" --aa analytic --rule nonexterior)
  awk -v n="$(basename "$scene" .svg)" -v a="$a" -v e="$e" -v nz="$nz" -v ne="$ne" \
    'BEGIN { printf "| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", n, a, e, e / a, nz, ne, ne / nz }'
done
