#!/usr/bin/env bash
# CTest entry conformance_sample_needs_shared: runs scripts/conformance.sh on the fixed sample listed in
# tests/conformance_sample.tsv (every tenth test of the suite, with the status it had when the sample was made)
# and fails when a test marked pass no longer passes. It needs ../shared/conformance: under CI=true a missing
# suite is a failure; elsewhere the test is skipped (exit 77) with the reason printed.
# usage: tests/conformance_sample.sh VRASTER_BINARY OUT_DIR
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bash "$here/../scripts/conformance.sh" --vraster "$1" --out "$2" --expect "$here/conformance_sample.tsv" -j 2
rc=$?
if ((rc == 3)); then
  if [[ ${CI:-} == true ]]; then
    echo "conformance_sample_needs_shared: FAILED: CI=true but ../shared/conformance (the resvg suite) is missing" >&2
    exit 1
  fi
  echo "conformance_sample_needs_shared: SKIPPED: ../shared/conformance (the resvg suite) is not next to this checkout"
  exit 77
fi
exit "$rc"
