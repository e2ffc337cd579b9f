#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds examples/client_app
# against it with find_package(freeform), proving the package config works.
#   package_test.sh BUILD_DIR SOURCE_DIR [CMAKE_ARGS...]
# (CMAKE_ARGS carry the build's own flags, e.g. sanitizers, to the consumer.)
set -euo pipefail
build_dir=$1
source_dir=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
cmake -S "$source_dir/examples/client_app" -B "$work/app" \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$work/app" >/dev/null
test -x "$work/app/client_app"
echo "client_app built against the installed freeform package"
