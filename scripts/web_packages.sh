#!/usr/bin/env bash
# Installs the npm packages of web/package-lock.json into web/node_modules,
# exactly as locked: esbuild and three.js, which the build bundles into the
# playground page that freeformd embeds (web/CMakeLists.txt), and, unless
# --omit-dev, playwright-core, which drives Debian's chromium in the browser
# test (tests/browser/). Runs `npm ci` only when the lock file changed since
# the last install; the build itself downloads nothing.
#   scripts/web_packages.sh [--omit-dev]
set -euo pipefail
cd "$(dirname "$0")/../web"
omit=()
case "${1:-}" in
  --omit-dev) omit=(--omit=dev) ;;
  "") ;;
  *) echo "usage: $0 [--omit-dev]" >&2; exit 2 ;;
esac
stamp=node_modules/.freeform-installed
wanted="$(sha256sum package-lock.json | cut -d' ' -f1) ${omit[*]:-all}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$wanted" ]; then
  echo "web_packages: web/node_modules is up to date"
  exit 0
fi
npm ci --no-audit --no-fund "${omit[@]}"
echo "$wanted" >"$stamp"
