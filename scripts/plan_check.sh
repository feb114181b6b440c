#!/usr/bin/env bash
# Renders every test of the resvg suite (../shared/conformance/resvg) planned and with --no-plan, and reports the
# largest channel difference between the two per test (the plan must never change the picture) and how much the
# plans culled, dropped and folded. usage: scripts/plan_check.sh [VRASTER_BINARY]
set -uo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
vraster=${1:-$repo/build/vraster}
suite=${VRASTER_CONFORMANCE:-$repo/../shared/conformance}/resvg
[[ -d $suite ]] || { echo "plan_check.sh: $suite is missing" >&2; exit 3; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tests=0 differ=0 worst=0 culled=0 dropped=0 folded=0
while IFS= read -r f; do
  timeout 10 "$vraster" render "$f" -o "$work/planned.png" -w 300 --quiet 2>/dev/null || continue
  timeout 10 "$vraster" render "$f" -o "$work/naive.png" -w 300 --quiet --no-plan 2>/dev/null || continue
  e=$("$vraster" compare "$work/naive.png" "$work/planned.png" | sed -n 's/.*max_error=\([0-9]*\).*/\1/p')
  summary=$(timeout 10 "$vraster" explain "$f" -w 300 --quiet --json | grep -o '"summary":{[^}]*}')
  field() { sed -n "s/.*\"$1\":\([0-9]*\).*/\1/p" <<<"$summary"; }
  tests=$((tests + 1)) culled=$((culled + $(field culled))) dropped=$((dropped + $(field layers_dropped)))
  folded=$((folded + $(field layers_folded)))
  if ((e > 0)); then differ=$((differ + 1)); echo "differs by $e: ${f#"$suite"/}"; fi
  ((e > worst)) && worst=$e
done < <(find "$suite" -name '*.svg' | sort)
echo "plan_check: $tests tests, $differ differ (largest difference $worst/255); plans culled $culled calls," \
     "dropped $dropped layers, folded $folded"
((worst <= 1))
