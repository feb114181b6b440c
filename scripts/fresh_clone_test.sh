#!/usr/bin/env bash
# The README's promise checked the way a new user meets it: a clone of this checkout's HEAD, in an empty temporary
# folder with no ../shared beside it, passes the README's test command (`bash scripts/run.sh test`).
# Only committed files take part (uncommitted changes are not in the clone). The folder is removed afterwards
# unless KEEP_FRESH_CLONE=1.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
commit=$(git -C "$repo" rev-parse HEAD)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/vraster-fresh-clone.XXXXXX")
if [[ ${KEEP_FRESH_CLONE:-0} != 1 ]]; then
  trap 'rm -rf "$tmp"' EXIT
fi

echo "fresh clone: $commit into $tmp/vraster"
git clone --quiet --no-checkout "$repo" "$tmp/vraster"
git -C "$tmp/vraster" checkout --quiet --detach "$commit"
if [[ -e $tmp/shared ]]; then
  echo "fresh clone: $tmp/shared exists; the check needs a folder without it" >&2
  exit 1
fi
cd "$tmp/vraster"
# Tests named *_needs_shared skip (instead of failing under CI=true) when told the run has no ../shared on purpose.
VRASTER_WITHOUT_SHARED=1 bash scripts/run.sh test
