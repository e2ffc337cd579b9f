#!/usr/bin/env bash
# Measures freeformd's HTTP/JSON gateway against its own gRPC listener in one
# run, with one client program (bench/http_load) for both, and prints the
# table of docs/benchmarks.md with each ratio and its target.
#
#   scripts/http_ratio.sh [ROUNDS]
#
# FREEFORMD=path  use this freeformd binary instead of building
#               build/release/server/freeformd.
# A missed target prints MISSED but still exits 0 (this is a measuring tool).
# Exit 1 if the server did not start or a call failed, 2 if the build failed.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 2

rounds="${1:-3}"
bin=build/release
targets=(http_load)
freeformd="${FREEFORMD:-$bin/server/freeformd}"
[ -z "${FREEFORMD:-}" ] && targets+=(freeformd)
if ! bash scripts/build.sh release --target "${targets[@]}" >&2; then
  echo "build failed" >&2
  exit 2
fi

work=$(mktemp -d /tmp/http_ratio.XXXXXX)
"$freeformd" --listen=127.0.0.1:0 --http_listen=127.0.0.1:0 \
  --log_level=warn >"$work/out" 2>"$work/log" &
pid=$!
# shellcheck disable=SC2317  # runs from the EXIT trap
stop_server() {
  kill -TERM "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  rm -rf "$work"
}
trap stop_server EXIT
for _ in $(seq 1 100); do
  grep -q "http listening" "$work/out" 2>/dev/null && break
  sleep 0.05
done
grpc=$(sed -n 's/^freeformd listening on \(.*\)$/\1/p' "$work/out")
http=$(sed -n 's/^freeformd http listening on \(.*\)$/\1/p' "$work/out")
if [ -z "$grpc" ] || [ -z "$http" ]; then
  echo "freeformd did not start:" >&2
  cat "$work/log" >&2
  exit 1
fi
"$bin/bench/http_load" --grpc_target="$grpc" --http_target="$http" \
  --rounds="$rounds"
