#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time (the `fuzz` ctest label):
#   run_fuzzer.sh DEFAULT_SECONDS FUZZER WORK_DIR REGRESSIONS_DIR [SEED_DIR...]
# libFuzzer flags come from $FREEFORM_FUZZ_TARGET_FLAGS (the test's own,
# set by tests/fuzz/CMakeLists.txt) and then $FREEFORM_FUZZ_FLAGS (yours).
# $FREEFORM_FUZZ_TARGET_ENV holds NAME=value words for the fuzzer's
# environment (FREEFORM_FUZZ_OPEN_FINDINGS in tests/fuzz/CMakeLists.txt);
# FREEFORM_FUZZ_STRICT=1 leaves them out. Oracle findings that are only
# logged (FREEFORM_FUZZ_ORACLES=log) are saved in WORK_DIR/findings/.
# First replays every input of REGRESSIONS_DIR (when it exists), then fuzzes
# for $FREEFORM_FUZZ_SECONDS (else DEFAULT_SECONDS), or for
# $FREEFORM_FUZZ_RUNS executions when that is set, into WORK_DIR/corpus,
# starting from that corpus and the seed folders. Crashes, leaks, timeouts
# and OOMs go to WORK_DIR/artifacts/ and fail the test.
set -euo pipefail
default_seconds=$1 fuzzer=$2 work=$3 regressions=$4
shift 4
seconds=${FREEFORM_FUZZ_SECONDS:-$default_seconds}
mkdir -p "$work/corpus" "$work/artifacts" "$work/findings"
export FREEFORM_FUZZ_FINDINGS="$work/findings"
if [ -z "${FREEFORM_FUZZ_STRICT:-}" ] && [ -n "${FREEFORM_FUZZ_TARGET_ENV:-}" ]; then
  # shellcheck disable=SC2086  # NAME=value words
  export ${FREEFORM_FUZZ_TARGET_ENV}
  echo "open findings: ${FREEFORM_FUZZ_TARGET_ENV} (FREEFORM_FUZZ_STRICT=1 for none)"
fi
# One input may take this long before it counts as a hang; the RPC
# harness's own deadline (5 s) is shorter, so a slow call is reported by
# the harness with its status first.
options=(-timeout=25 -rss_limit_mb=2560 -artifact_prefix="$work/artifacts/"
  -print_final_stats=1)
# shellcheck disable=SC2206  # flags are words
options+=(${FREEFORM_FUZZ_TARGET_FLAGS:-} ${FREEFORM_FUZZ_FLAGS:-})
if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
  echo "replaying $regressions"
  "$fuzzer" "${options[@]}" -runs=0 "$regressions"
fi
seeds=()
for dir in "$@"; do [ -d "$dir" ] && seeds+=("$dir"); done
if [ -n "${FREEFORM_FUZZ_RUNS:-}" ]; then
  options+=(-runs="$FREEFORM_FUZZ_RUNS")
else
  options+=(-max_total_time="$seconds")
fi
exec "$fuzzer" "${options[@]}" "$work/corpus" "${seeds[@]}"
