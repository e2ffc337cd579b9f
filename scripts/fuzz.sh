#!/usr/bin/env bash
# Builds the libFuzzer targets (the fuzz preset) and fuzzes each one for
# SECONDS (default 600), two at a time: the long run of docs/fuzzing.md.
#   scripts/fuzz.sh [SECONDS] [REGEX]
# REGEX picks tests by name (e.g. CurveService_Evaluate or core_). With
# FREEFORM_FUZZ_RUNS=N set, each target instead runs N executions.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
filter="${2:-}"
bash scripts/build.sh fuzz
# Each fuzzer stops itself (-max_total_time or -runs) and libFuzzer's
# -timeout catches a hung input, so ctest's limit per test is a day.
args=(--preset fuzz -j 2 --timeout 86400)
[ -n "$filter" ] && args+=(-R "$filter")
FREEFORM_FUZZ_SECONDS="$seconds" ctest "${args[@]}"
