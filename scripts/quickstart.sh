#!/usr/bin/env bash
# Quick start: installs what is missing, builds freeformd and the freeform
# CLI, starts the server on a free local port, evaluates the cubic Bezier
# (0,0) (1,2) (3,2) (4,0) at t = 0, 0.5, 1 with its first derivative through
# the CLI, prints the answer and stops the server.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh release --target freeformd freeform

server_out=$(mktemp)
server_log=$(mktemp)
build/release/server/freeformd --listen=127.0.0.1:0 >"$server_out" 2>"$server_log" &
server_pid=$!
trap 'kill "$server_pid" 2>/dev/null || true; rm -f "$server_out" "$server_log"' EXIT
for _ in $(seq 1 100); do
  grep -q "listening on" "$server_out" && break
  sleep 0.1
done
address=$(awk '/listening on/ {print $4}' "$server_out")
echo "freeformd is serving on $address"
echo
echo "$ freeform eval --address $address --file examples/cubic_bezier.json --format csv"
build/release/client/freeform eval --address "$address" \
  --file examples/cubic_bezier.json --format csv
echo
echo "$ freeform eval --address $address --file examples/cubic_bezier.json"
build/release/client/freeform eval --address "$address" \
  --file examples/cubic_bezier.json
kill -TERM "$server_pid"
wait "$server_pid"
echo
echo "freeformd's log (access log lines, then the graceful stop):"
cat "$server_log"
