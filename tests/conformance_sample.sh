#!/usr/bin/env bash
# CTest entries conformance_sample_needs_shared and conformance_text_sample_needs_shared: run
# scripts/conformance.sh on a fixed sample, tests/conformance_sample.tsv (every tenth test of resvg/) or
# tests/conformance_text_sample.tsv (every tenth test of resvg-text/, run with the suite's fonts only), each
# with the status it had when the sample was made, and fail when a test marked pass no longer passes. It needs ../shared/conformance: under CI=true a missing
# suite is a failure, unless VRASTER_WITHOUT_SHARED=1 says the run is meant to have none (the fresh-clone check);
# elsewhere the test is skipped (exit 77) with the reason printed. The time cap is 30 s, not the script's 1 s:
# this entry also runs in Debug sanitizer builds, and it guards against regressions and hangs, not slowness
# (the full Release run of scripts/conformance.sh measures that).
# usage: tests/conformance_sample.sh VRASTER_BINARY OUT_DIR [SAMPLE.tsv]
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bash "$here/../scripts/conformance.sh" --vraster "$1" --out "$2" --expect "${3:-$here/conformance_sample.tsv}" -j 2 --cap 30
rc=$?
if ((rc == 3)); then
  if [[ ${CI:-} == true && ${VRASTER_WITHOUT_SHARED:-} != 1 ]]; then
    echo "conformance_sample_needs_shared: FAILED: CI=true but ../shared/conformance (the resvg suite) is missing" >&2
    exit 1
  fi
  echo "conformance_sample_needs_shared: SKIPPED: ../shared/conformance (the resvg suite) is not next to this checkout" \
       "${VRASTER_WITHOUT_SHARED:+(VRASTER_WITHOUT_SHARED=1: a run meant to have none)}"
  exit 77
fi
exit "$rc"
