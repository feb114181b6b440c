#!/usr/bin/env bash
# One entry point for a fresh machine:
#   scripts/run.sh demo   install what is missing, build (Release), render the embedded demo scene to a PNG
#   scripts/run.sh test   install what is missing, build (Release), run every test through CTest
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
job=${1:-}
case "$job" in
  demo|test) ;;
  *) echo "usage: scripts/run.sh demo|test" >&2; exit 2 ;;
esac

start=$SECONDS
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"

if [[ $job == demo ]]; then
  mkdir -p out
  ./build/vraster demo -o out/vraster-demo.png
else
  status=0
  ctest --test-dir build --output-on-failure -j"$jobs" || status=$?
  echo "run.sh test: setup, build and tests took $((SECONDS - start)) s (wall time)"
  exit "$status"
fi
