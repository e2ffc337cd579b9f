#!/usr/bin/env bash
# Installs what is missing, builds everything (release preset) and runs
# every test with ctest, then builds the libFuzzer targets (fuzz preset) and
# fuzzes each briefly (ctest label `fuzz`, docs/fuzzing.md). Pass a preset
# to test only that build, e.g.
#   scripts/test.sh asan
# Each step's wall time goes to stderr at the end, to see where CI's time
# goes.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
timings=()
# step NAME COMMAND...: runs COMMAND and records its wall time.
step() {
  local name=$1 start=$SECONDS
  shift
  "$@"
  timings+=("$(printf '%-22s %5d s' "$name" $((SECONDS - start)))")
}
report() {
  local line
  echo "test.sh: wall time per step" >&2
  for line in "${timings[@]}"; do echo "  $line" >&2; done
}
trap report EXIT
step "install + $preset build" bash scripts/build.sh "$preset"
step "$preset tests" ctest --preset "$preset" -j "$(nproc)"
if [ "$#" -eq 0 ]; then
  step "fuzz build" bash scripts/build.sh fuzz
  step "fuzz runs" ctest --preset fuzz -j "$(nproc)"
fi
