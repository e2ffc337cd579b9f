#!/usr/bin/env bash
# Measures freeformd against the bare gRPC transport (transport_echo_server)
# in one run, with one client (service_load) for both, and prints each ratio
# with its target. The two servers run side by side on free loopback ports and
# the workloads alternate between them, round after round; each figure is the
# best of its rounds.
#
#   scripts/service_ratio.sh [ROUNDS] [--s3] [--seconds=S]
#
# ROUNDS        rounds of S1 latency, S1 throughput (16 outstanding calls),
#               S2 streamed and S2 unary, on both servers (default 3).
# --s3          then also run S3 (mixed load over every RPC) on freeformd.
# --seconds=S   duration of S3 (default 60).
# FREEFORMD=path  use this freeformd binary instead of building
#               build/release/server/freeformd.
#
# A missed target prints MISSED but still exits 0 (this is a measuring tool).
# Exit 1 if a server did not start or a call failed, 2 if the build failed.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 2

rounds=3
s3=0
s3_seconds=60
for arg in "$@"; do
  case "$arg" in
    --s3) s3=1 ;;
    --seconds=*) s3_seconds="${arg#--seconds=}" ;;
    [0-9]*) rounds="$arg" ;;
    *) echo "usage: $0 [ROUNDS] [--s3] [--seconds=S]" >&2; exit 2 ;;
  esac
done

bin=build/release
if [ -n "${FREEFORMD:-}" ]; then
  freeformd="$FREEFORMD"
  targets=(service_load transport_echo_server)
else
  freeformd="$bin/server/freeformd"
  targets=(freeformd service_load transport_echo_server)
fi
if ! bash scripts/build.sh release --target "${targets[@]}" >&2; then
  echo "build failed (set FREEFORMD=path to use an existing freeformd)" >&2
  exit 2
fi
load="$bin/bench/service_load"
echo_server="$bin/bench/echo/transport_echo_server"

work=$(mktemp -d /tmp/service_ratio.XXXXXX)
pids=()
# shellcheck disable=SC2317  # runs from the EXIT trap
stop_servers() {
  local pid
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null; done
  for _ in $(seq 1 50); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ "$alive" = 0 ] && break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -KILL "$pid" 2>/dev/null; done
  rm -rf "$work"
}
trap stop_servers EXIT

# start_server NAME COMMAND...: starts it in the background and sets
# `address` to the 127.0.0.1:PORT it reports listening on (waits up to 20 s).
start_server() {
  local name=$1
  shift
  "$@" >"$work/$name.out" 2>"$work/$name.err" &
  local pid=$!
  pids+=("$pid")
  address=""
  for _ in $(seq 1 200); do
    kill -0 "$pid" 2>/dev/null || break
    address=$(grep -oE 'listening on 127\.0\.0\.1:[0-9]+' "$work/$name.out" |
      head -1 | sed 's/^listening on //')
    [ -n "$address" ] && return 0
    sleep 0.1
  done
  echo "$name did not start:" >&2
  cat "$work/$name.err" >&2
  return 1
}

start_server echo "$echo_server" --listen=127.0.0.1:0 --max_seconds=7200 ||
  exit 1
echo_address=$address
start_server freeformd "$freeformd" --listen=127.0.0.1:0 --log_level=warn ||
  exit 1
ff_address=$address
echo "echo on $echo_address, freeformd ($freeformd) on $ff_address"

failed=0
figures="$work/figures.txt"
# measure WORKLOAD KIND: one service_load run; appends "WORKLOAD KIND figures".
measure() {
  local workload=$1 kind=$2 address=$ff_address args=()
  [ "$kind" = echo ] && address=$echo_address
  case "$workload" in
    s1_latency) args=(--mode=latency --iters=10000) ;;
    s1_throughput) args=(--mode=throughput --outstanding=16 --seconds=3) ;;
    s2_stream) args=(--mode=stream --iters=15) ;;
    s2_unary) args=(--mode=unary_bulk --iters=15) ;;
  esac
  local out
  out=$("$load" --target="$address" --target_kind="$kind" "${args[@]}" \
    2>"$work/load.err")
  local rc=$?
  printf '  %-14s %-9s %s\n' "$workload" "$kind" "$out"
  if [ "$rc" != 0 ]; then
    failed=1
    sed 's/^/    /' "$work/load.err"
    return
  fi
  echo "$workload $kind $out" >>"$figures"
}

workloads=(s1_latency s1_throughput s2_stream s2_unary)
for round in $(seq 1 "$rounds"); do
  echo "round $round of $rounds"
  order=(echo freeform)
  [ $((round % 2)) = 0 ] && order=(freeform echo)
  for workload in "${workloads[@]}"; do
    for kind in "${order[@]}"; do measure "$workload" "$kind"; done
  done
done

# best WORKLOAD KIND KEY min|max: the best figure KEY=value over the rounds.
best() {
  awk -v w="$1" -v k="$2" -v key="$3" -v how="$4" '
    $1 == w && $2 == k {
      for (i = 3; i <= NF; ++i) if (split($i, kv, "=") == 2 && kv[1] == key) {
        v = kv[2] + 0
        if (n == 0 || (how == "min" ? v < b : v > b)) b = v
        ++n
      }
    }
    END {
      if (!n) printf "-"
      else printf (b >= 1000 ? "%.0f" : b >= 100 ? "%.1f" : "%.2f"), b
    }' "$figures" 2>/dev/null
}

# row LABEL WORKLOAD KEY min|max OP TARGET
row() {
  local e f
  e=$(best "$2" echo "$3" "$4")
  f=$(best "$2" freeform "$3" "$4")
  awk -v label="$1" -v e="$e" -v f="$f" -v op="$5" -v t="$6" 'BEGIN {
    if (e == "-" || f == "-" || e + 0 == 0) {
      printf "%-32s %10s %10s %7s  %2s %-4s %s\n", label, e, f, "-", op, t,
        "NO DATA"
      exit
    }
    r = f / e
    ok = (op == "<=") ? (r <= t) : (r >= t)
    printf "%-32s %10s %10s %7.2f  %2s %-4s %s\n", label, e, f, r, op, t,
      ok ? "ok" : "MISSED"
  }'
}

echo
echo "best of $rounds round(s); ratio = freeform / echo"
printf '%-32s %10s %10s %7s  %-7s %s\n' workload echo freeform ratio target \
  result
row "S1 p50 latency (us)" s1_latency p50_us min "<=" 1.2
row "S1 calls/s, 16 outstanding" s1_throughput calls_per_s max ">=" 0.8
row "S2 10^6 points streamed (ms)" s2_stream best_ms min "<=" 1.3
row "S2 10^6 points unary (ms)" s2_unary best_ms min "<=" 1.3

if [ "$s3" = 1 ]; then
  echo
  echo "S3: mixed load on freeformd, 64 callers, ${s3_seconds} s"
  if ! "$load" --target="$ff_address" --target_kind=freeform --mode=mixed \
    --callers=64 --seconds="$s3_seconds"; then
    echo "S3: calls FAILED (see the errors column)"
    failed=1
  fi
fi

[ "$failed" = 0 ] || echo "some calls FAILED: the figures above are incomplete"
exit "$failed"
