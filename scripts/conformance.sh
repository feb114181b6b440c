#!/usr/bin/env bash
# Renders the resvg conformance tests (../shared/conformance/resvg, and the text tests in resvg-text) with the
# vraster CLI, compares each with its reference PNG under the pass rule of `vraster compare`, and writes a report
# with one section per suite:
#   OUT/summary.md    pass counts per category and per folder, every test that does not pass and why
#   OUT/index.html    reference / ours / difference side by side for each failure
#   OUT/results.tsv   one line per test: path, category, folder, status, milliseconds, detail
# Status: pass, fail (the images differ), error (exit 2: the document was refused), crash (any other exit or a
# signal), slow (over the time cap, 1 s), noref (no reference PNG), left-out (a test that needs a font the suite
# does not bundle: manifest.tsv, column font_files_not_bundled, or the table left_out below; not run, not counted).
# The text tests run with the suite's fonts only (--font-dir fonts --no-system-fonts), the harness's generic
# families (serif Noto Serif, sans-serif Noto Sans, cursive Yellowtail, fantasy Sedgwick Ave Display, monospace
# Noto Mono) and its default font-size 12, so their results do not depend on this machine's fonts.
#
# usage: scripts/conformance.sh [-j N] [--out DIR] [--vraster BIN] [--tests LIST] [--expect FILE] [--cap SECONDS]
#                               [--suite resvg|resvg-text|all]
#   --tests LIST   only the tests listed (paths relative to ../shared/conformance, one a line)
#   --expect FILE  lines "STATUS<TAB>PATH": runs those tests; exits 1 if one listed as pass no longer passes
# The suite is ../shared/conformance from the repository root (or from the main checkout of a git worktree);
# VRASTER_CONFORMANCE overrides it. Exit status 3: the suite is missing.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
suite=${VRASTER_CONFORMANCE:-$repo/../shared/conformance}
# In a git worktree elsewhere, ../shared is next to the main checkout.
if [[ -z ${VRASTER_CONFORMANCE:-} && ! -d $suite ]]; then
  common=$(git -C "$repo" rev-parse --path-format=absolute --git-common-dir 2>/dev/null || true)
  [[ -n $common && -d $common/../../shared/conformance ]] && suite=$common/../../shared/conformance
fi
# Tests left out besides manifest.tsv's, one a line: test path <TAB> reason (checked by hand, see
# docs/conformance.md). Printed with the reason in the report; not run, not counted.
left_out=$(cat <<'EOF'
resvg-text/text/writing-mode/mixed-languages-with-tb-and-underline.svg	needs a font the suite does not bundle: no font in fonts/ has 本 (U+672C); the reference's is M PLUS 1p
EOF
)
jobs=2
out=$repo/out/conformance
vraster=$repo/build/vraster
tests_file=
expect_file=
cap=1
suites=all

while (($#)); do
  case $1 in
    -j) jobs=$2; shift 2 ;;
    -j*) jobs=${1#-j}; shift ;;
    --out) out=$2; shift 2 ;;
    --vraster) vraster=$2; shift 2 ;;
    --tests) tests_file=$2; shift 2 ;;
    --expect) expect_file=$2; shift 2 ;;
    --cap) cap=$2; shift 2 ;;
    --suite) suites=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "conformance.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [[ ! -d $suite/resvg ]]; then
  echo "conformance.sh: the conformance suite is missing: no folder $suite/resvg" >&2
  exit 3
fi
[[ -x $vraster ]] || { echo "conformance.sh: no vraster binary at $vraster (build it, or pass --vraster)" >&2; exit 2; }
suite=$(cd "$suite" && pwd)
vraster=$(cd "$(dirname "$vraster")" && pwd)/$(basename "$vraster")

rm -rf "$out"
mkdir -p "$out/ours" "$out/diff" "$out/ref" "$out/results" "$out/logs"
out=$(cd "$out" && pwd)

list=$out/tests.txt
if [[ -n $expect_file ]]; then
  cut -f2 "$expect_file" | grep -v '^$' > "$list"
elif [[ -n $tests_file ]]; then
  grep -v '^$' "$tests_file" > "$list"
else
  case $suites in
    all) dirs=(resvg resvg-text) ;;
    resvg|resvg-text) dirs=("$suites") ;;
    *) echo "conformance.sh: --suite: expected resvg, resvg-text or all, got '$suites'" >&2; exit 2 ;;
  esac
  (cd "$suite" && for d in "${dirs[@]}"; do [[ -d $d ]] && find "$d" -name '*.svg'; done | LC_ALL=C sort) > "$list"
fi

# One test: renders it 300 px wide (the references' width), compares, writes results/NAME.tsv.
run_one() {
  local rel=$1 name status detail ms rc
  name=${rel#resvg/}
  name=${name%.svg}
  name=${name//\//__}
  local -a extra=()
  if [[ $rel == resvg-text/* ]]; then
    # The resvg text harness: its fonts only, its generic families, font-size 12.
    extra=(--font-dir "$suite/fonts" --no-system-fonts --serif-family "Noto Serif" --sans-serif-family "Noto Sans"
           --cursive-family Yellowtail --fantasy-family "Sedgwick Ave Display" --monospace-family "Noto Mono"
           --default-family serif --default-font-size 12)
  fi
  local reason
  reason=$(awk -F'\t' -v r="$rel" '$1 == r && $9 != "" && $9 != "-" { print "needs a font the suite does not bundle: " $9 }' \
             "$suite/manifest.tsv")
  [[ -n $reason ]] || reason=$(awk -F'\t' -v r="$rel" '$1 == r { print $2 }' <<<"$left_out")
  if [[ -n $reason ]]; then
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$rel" "$(cut -d/ -f2 <<<"$rel")" "$(cut -d/ -f2-3 <<<"$rel")" left-out 0 "$reason" \
      >"$out/results/$name.tsv"
    return
  fi
  local svg=$suite/$rel ref=$suite/${rel%.svg}.png ours=$out/ours/$name.png log=$out/logs/$name.txt
  local category folder
  category=$(cut -d/ -f2 <<<"$rel")
  folder=$(cut -d/ -f2-3 <<<"$rel")
  local start end
  start=$(date +%s%N)
  set +e
  timeout --kill-after=1 "$cap" "$vraster" render "$svg" -o "$ours" -w 300 --quiet --allow-dir "$suite" "${extra[@]}" >"$log" 2>&1
  rc=$?
  set -e
  end=$(date +%s%N)
  ms=$(((end - start) / 1000000))
  detail=
  if [[ ! -f $ref ]]; then
    status=noref
  elif ((rc == 124 || rc == 137)); then
    status=slow; detail="over ${cap} s"
  elif ((rc == 2)); then
    status=error; detail=$(head -c 300 "$log" | head -n 1 | sed "s|$suite/||g")
  elif ((rc != 0)); then
    status=crash; detail="exit status $rc"
  else
    set +e
    detail=$("$vraster" compare "$ref" "$ours" --diff "$out/diff/$name.png" 2>&1)
    rc=$?
    set -e
    case $rc in
      0) status=pass ;;
      1) status=fail ;;
      *) status=crash; detail="compare: $detail" ;;
    esac
    detail=${detail#pass }
    detail=${detail#fail }
  fi
  if [[ $status != pass ]]; then
    [[ -f $ref ]] && cp "$ref" "$out/ref/$name.png"
  else
    rm -f "$out/diff/$name.png" "$out/ours/$name.png"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$rel" "$category" "$folder" "$status" "$ms" "${detail//$'\t'/ }" \
    >"$out/results/$name.tsv"
}
export -f run_one
export suite out vraster cap left_out

tr '\n' '\0' <"$list" | xargs -0 -P "$jobs" -n 1 bash -c 'run_one "$1"' run_one
LC_ALL=C sort "$out"/results/*.tsv >"$out/results.tsv"
rm -rf "$out/results"

# ---- summary.md ----
# Counts leave out the left-out tests (they need fonts the suite does not have).
counted=$(awk -F'\t' '$4 != "left-out"' "$out/results.tsv" | wc -l)
total=$counted
passed=$(awk -F'\t' '$4 == "pass"' "$out/results.tsv" | wc -l)
section() {  # one suite's tables: $1 = resvg or resvg-text
  local rows
  rows=$(awk -F'\t' -v s="$1" 'index($1, s "/") == 1' "$out/results.tsv")
  [[ -z $rows ]] && return
  local n p l
  n=$(awk -F'\t' '$4 != "left-out"' <<<"$rows" | wc -l)
  p=$(awk -F'\t' '$4 == "pass"' <<<"$rows" | wc -l)
  l=$(awk -F'\t' '$4 == "left-out"' <<<"$rows" | wc -l)
  echo "## $1: $p of $n pass ($(awk -v p="$p" -v t="$n" 'BEGIN { printf "%.1f", t ? 100 * p / t : 0 }')%)${l:+, $l left out}"
  echo
  echo "| category | pass | total | % | fail | error | crash | slow |"
  echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  awk -F'\t' '$4 != "left-out" { n[$2]++; s[$2, $4]++ } END {
      for (c in n) printf "| %s | %d | %d | %.1f | %d | %d | %d | %d |\n", c, s[c, "pass"], n[c], 100 * s[c, "pass"] / n[c],
                          s[c, "fail"], s[c, "error"], s[c, "crash"], s[c, "slow"] }' <<<"$rows" | LC_ALL=C sort
  echo
  echo "| folder | pass | total |"
  echo "| --- | ---: | ---: |"
  awk -F'\t' '$4 != "left-out" { n[$3]++; if ($4 == "pass") p[$3]++ } END { for (f in n) printf "| %s | %d | %d |\n", f, p[f], n[f] }' \
    <<<"$rows" | LC_ALL=C sort
  echo
}
{
  echo "# Conformance: $passed of $total pass ($(awk -v p="$passed" -v t="$total" 'BEGIN { printf "%.1f", t ? 100 * p / t : 0 }')%)"
  echo
  echo "Suite: ../shared/conformance, rule: \`vraster compare\`, time cap ${cap} s, $(date -u +%Y-%m-%d)."
  echo
  section resvg
  section resvg-text
  echo "## Tests that do not pass"
  echo
  awk -F'\t' '$4 != "pass" && $4 != "left-out" { printf "- %s: %s %s\n", $1, $4, $6 }' "$out/results.tsv"
  echo
  echo "## Left out (not run, not counted)"
  echo
  awk -F'\t' '$4 == "left-out" { printf "- %s: %s\n", $1, $6 }' "$out/results.tsv"
} >"$out/summary.md"

# ---- index.html ----
html_escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }
{
  cat <<'EOF'
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>vraster conformance</title>
<style>
body { font: 14px sans-serif; margin: 1em; }
table.sum td, table.sum th { padding: 2px 8px; text-align: right; }
table.sum td:first-child { text-align: left; }
.test { margin: 1.2em 0; border-top: 1px solid #ccc; padding-top: .4em; }
.test h3 { font-size: 14px; margin: 0 0 .3em 0; }
.status { font-weight: bold; color: #b00; }
.row { display: flex; gap: 12px; align-items: flex-start; }
figure { margin: 0; }
figcaption { font-size: 12px; color: #555; }
img, .missing { width: 300px; border: 1px solid #999;
  background: repeating-conic-gradient(#ddd 0% 25%, #fff 0% 50%) 50% / 16px 16px; }
.missing { height: 300px; display: flex; align-items: center; justify-content: center; color: #777; }
</style></head><body>
EOF
  echo "<h1>vraster conformance: $passed of $total pass</h1>"
  echo '<table class="sum"><tr><th>category</th><th>pass</th><th>total</th><th>fail</th><th>error</th><th>crash</th><th>slow</th></tr>'
  awk -F'\t' '$4 != "left-out" { split($1, p, "/"); k = p[1] "/" $2; n[k]++; s[k, $4]++ } END {
      for (c in n) printf "<tr><td>%s</td><td>%d</td><td>%d</td><td>%d</td><td>%d</td><td>%d</td><td>%d</td></tr>\n", c,
                          s[c, "pass"], n[c], s[c, "fail"], s[c, "error"], s[c, "crash"], s[c, "slow"] }' \
    "$out/results.tsv" | LC_ALL=C sort
  echo '</table>'
  echo '<p>Each failure: the reference, our rendering, and the difference (red: a channel differs by more than'
  echo '96/255; orange: off by more than 16/255 after the 3x3 neighbourhood excuse; grey: the reference, faded).</p>'
  while IFS=$'\t' read -r rel _category _folder status ms detail; do
    [[ $status == pass || $status == left-out ]] && continue
    name=${rel#resvg/}
    name=${name%.svg}
    name=${name//\//__}
    echo "<div class=\"test\" id=\"$name\"><h3>$(html_escape <<<"$rel") <span class=\"status\">$status</span> (${ms} ms)</h3>"
    echo "<div>$(html_escape <<<"$detail")</div><div class=\"row\">"
    for kind in ref ours diff; do
      label=$([[ $kind == ref ]] && echo reference || echo "$kind")
      if [[ -f $out/$kind/$name.png ]]; then
        echo "<figure><img src=\"$kind/$name.png\" alt=\"$label\" loading=\"lazy\"><figcaption>$label</figcaption></figure>"
      else
        echo "<figure><div class=\"missing\">no image</div><figcaption>$label</figcaption></figure>"
      fi
    done
    echo "</div></div>"
  done <"$out/results.tsv"
  echo '</body></html>'
} >"$out/index.html"

sed -n '1,/^## Tests that/p' "$out/summary.md" | sed '$d'
echo "report: $out/summary.md, $out/index.html"

# ---- regressions against an expectation file ----
if [[ -n $expect_file ]]; then
  regressions=$(awk -F'\t' 'NR == FNR { if ($4 != "pass") now[$1] = $4 " " $6; next }
                            $1 == "pass" && ($2 in now) { print "  " $2 ": " now[$2] }' "$out/results.tsv" "$expect_file")
  improved=$(awk -F'\t' 'NR == FNR { if ($4 == "pass") ok[$1] = 1; next }
                         $1 != "pass" && ($2 in ok) { print "  " $2 }' "$out/results.tsv" "$expect_file")
  if [[ -n $improved ]]; then
    echo "conformance.sh: these now pass (mark them pass in $(basename "$expect_file")):"
    echo "$improved"
  fi
  if [[ -n $regressions ]]; then
    echo "conformance.sh: REGRESSION: tests that passed no longer pass:" >&2
    echo "$regressions" >&2
    exit 1
  fi
  echo "conformance.sh: no regression in $(basename "$expect_file")"
fi
