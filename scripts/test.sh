#!/usr/bin/env bash
# Installs what is missing, builds everything (release preset) and runs
# every test with ctest. Pass a preset to test another build, e.g.
#   scripts/test.sh asan
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
bash scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"
