#!/usr/bin/env bash
# Installs what is missing, builds everything (release preset) and runs
# every test with ctest, then builds the libFuzzer targets (fuzz preset) and
# fuzzes each briefly (ctest label `fuzz`, docs/fuzzing.md). Pass a preset
# to test only that build, e.g.
#   scripts/test.sh asan
# The fuzz build runs at the lowest priority beside the release build and
# its tests, so it takes only the CPU they leave idle (link steps, the end of
# a build, tests that wait on a server or on apt); its log is
# build/fuzz-build.log. Each step's wall time goes to stderr at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
timings=()
# step NAME COMMAND...: runs COMMAND and records its wall time.
step() {
  local name=$1 start=$SECONDS status=0
  shift
  "$@" || status=$?
  timings+=("$(printf '%-26s %5d s' "$name" $((SECONDS - start)))")
  return "$status"
}
report() {
  local line
  echo "test.sh: wall time per step" >&2
  for line in "${timings[@]}"; do echo "  $line" >&2; done
}
trap report EXIT

step "install" bash scripts/setup.sh
fuzz_build=""
if [ "$#" -eq 0 ]; then
  mkdir -p build
  nice -n 19 bash scripts/build.sh fuzz >build/fuzz-build.log 2>&1 &
  fuzz_build=$!
fi
step "$preset build" bash scripts/build.sh "$preset"
step "$preset tests" ctest --preset "$preset" -j "$(nproc)"
if [ -n "$fuzz_build" ]; then
  if ! step "fuzz build (rest of it)" wait "$fuzz_build"; then
    tail -n 60 build/fuzz-build.log >&2
    echo "test.sh: the fuzz build failed (build/fuzz-build.log)" >&2
    exit 1
  fi
  step "fuzz runs" ctest --preset fuzz -j "$(nproc)"
fi
