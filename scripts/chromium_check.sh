#!/usr/bin/env bash
# Cross-checks conformance tests against headless Chromium (a manual check: not part of CI or the tests).
# For each test it renders the SVG in Chromium as an <img> of exactly the reference's size (300 px wide) on a
# transparent page, renders ours as scripts/conformance.sh does, and compares Chromium's image with the
# reference and with ours under `vraster compare`. Chromium sees the suite's fonts only (a fontconfig file
# that lists ../shared/conformance/fonts and maps the generic families as the resvg harness does).
#
# usage: scripts/chromium_check.sh [--tests LIST] [--out DIR]
#   LIST: test paths relative to the suite, one a line; default: the tests that did not pass in the last
#   scripts/conformance.sh run (out/conformance/results.tsv). DIR: default out/chromium; it gets
#   chromium/NAME.png, ours/NAME.png and results.tsv (test, Chromium vs reference, Chromium vs ours).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
suite=${VRASTER_CONFORMANCE:-$repo/../shared/conformance}
if [[ -z ${VRASTER_CONFORMANCE:-} && ! -d $suite ]]; then  # a git worktree: ../shared is by the main checkout
  suite=$(git -C "$repo" rev-parse --path-format=absolute --git-common-dir)/../../shared/conformance
fi
out=$repo/out/chromium
tests=
while (($#)); do
  case $1 in
    --tests) tests=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "chromium_check.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
chromium=$(command -v chromium || command -v chromium-browser || true)
[[ -n $chromium ]] || { echo "chromium_check.sh: Chromium is not installed (apt-get install chromium)" >&2; exit 3; }
vraster=$repo/build/vraster
[[ -x $vraster ]] || { echo "chromium_check.sh: build vraster_cli first" >&2; exit 2; }
[[ -d $suite/resvg ]] || { echo "chromium_check.sh: no conformance suite at $suite" >&2; exit 3; }
suite=$(cd "$suite" && pwd)
mkdir -p "$out/chromium" "$out/ours" "$out/page"
out=$(cd "$out" && pwd)
if [[ -z $tests ]]; then
  tests=$out/tests.txt
  [[ -f $repo/out/conformance/results.tsv ]] || { echo "chromium_check.sh: run conformance.sh first" >&2; exit 2; }
  awk -F'\t' '$4 != "pass" && $4 != "left-out" { print $1 }' "$repo/out/conformance/results.tsv" >"$tests"
fi

# The suite's fonts only; Chromium's default families on Linux (Times New Roman, Arial, Monospace, Comic Sans
# MS, Impact) and the CSS generic names map to the harness's fonts; grey-scale antialiasing, no hinting.
alias_xml() {  # $1 = the family to use, the rest = the names that mean it
  local to=$1 name; shift
  for name; do
    echo "<match target=\"pattern\"><test name=\"family\"><string>$name</string></test>"
    echo "  <edit name=\"family\" mode=\"assign\" binding=\"strong\"><string>$to</string></edit></match>"
  done
}
{
  echo '<?xml version="1.0"?><!DOCTYPE fontconfig SYSTEM "fonts.dtd"><fontconfig>'
  echo "<dir>$suite/fonts</dir><cachedir>$out/fontconfig-cache</cachedir>"
  alias_xml "Noto Serif" serif "Times New Roman"
  alias_xml "Noto Sans" sans-serif Arial
  alias_xml "Noto Mono" monospace Monospace
  alias_xml Yellowtail cursive "Comic Sans MS"
  alias_xml "Sedgwick Ave Display" fantasy Impact
  echo '<match target="font"><edit name="antialias" mode="assign"><bool>true</bool></edit>'
  echo '  <edit name="hinting" mode="assign"><bool>false</bool></edit>'
  echo '  <edit name="rgba" mode="assign"><const>none</const></edit></match></fontconfig>'
} >"$out/fonts.conf"

sandbox=()
((EUID == 0)) && sandbox=(--no-sandbox)  # Chromium refuses to run as root with its sandbox
printf 'test\tchromium_vs_reference\tchromium_vs_ours\n' >"$out/results.tsv"
while read -r rel; do
  [[ -n $rel ]] || continue
  name=${rel#resvg/}; name=${name%.svg}; name=${name//\//__}
  ref=$suite/${rel%.svg}.png
  height=$(od -An -tu1 -j20 -N4 "$ref" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4 }')  # PNG IHDR
  page=$out/page/$name.html
  printf '<!DOCTYPE html><html><head><style>html, body { margin: 0; padding: 0; background: transparent; }
img { display: block; width: 300px; height: %spx; }</style></head><body><img src="file://%s"></body></html>\n' \
    "$height" "$suite/$rel" >"$page"
  rm -f "$out/chromium/$name.png"
  FONTCONFIG_FILE=$out/fonts.conf "$chromium" --headless "${sandbox[@]}" --disable-gpu --hide-scrollbars \
    --user-data-dir="$out/profile" --window-size=300,"$height" --default-background-color=00000000 \
    --screenshot="$out/chromium/$name.png" "file://$page" </dev/null >"$out/page/$name.log" 2>&1
  extra=()
  if [[ $rel == resvg-text/* ]]; then  # as scripts/conformance.sh runs the text tests
    extra=(--font-dir "$suite/fonts" --no-system-fonts --serif-family "Noto Serif" --sans-serif-family "Noto Sans"
           --cursive-family Yellowtail --fantasy-family "Sedgwick Ave Display" --monospace-family "Noto Mono"
           --default-family serif --default-font-size 12)
  fi
  "$vraster" render "$suite/$rel" -o "$out/ours/$name.png" -w 300 --quiet --allow-dir "$suite" "${extra[@]}" || true
  vs_ref=$("$vraster" compare "$ref" "$out/chromium/$name.png" 2>&1 || true)
  vs_ours=$("$vraster" compare "$out/ours/$name.png" "$out/chromium/$name.png" 2>&1 || true)
  printf '%s\t%s\t%s\n' "$rel" "$vs_ref" "$vs_ours" | tee -a "$out/results.tsv"
done <"$tests"
echo "results: $out/results.tsv"
