#!/usr/bin/env bash
# Installs what is missing, builds everything (release preset) and runs
# every test with ctest, then builds the libFuzzer targets (fuzz preset) and
# fuzzes each briefly (ctest label `fuzz`, docs/fuzzing.md). Pass a preset
# to test only that build, e.g.
#   scripts/test.sh asan
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
bash scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"
if [ "$#" -eq 0 ]; then
  bash scripts/build.sh fuzz
  ctest --preset fuzz -j "$(nproc)"
fi
