#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release), after installing
# any missing Debian packages. Extra arguments go to `cmake --build`.
#   scripts/build.sh [PRESET] [--target freeformd ...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
shift || true
bash scripts/setup.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)" "$@"
