#!/usr/bin/env bash
# Measures freeform against its peers in one run: builds the release
# configuration with the peer programs, runs the project's workload
# benchmarks (W1-W7 of docs/benchmarks.md) and the peers (OpenCASCADE, Eigen,
# scipy) on the same data one after the other, then the operations that have
# no peer (bench/operations_bench.cc), and prints a Markdown table of every
# workload: freeform's figure, every peer's, the ratio to the best peer and
# the target.
#
#   scripts/performance.sh [--install] [--runs=N] [--min-time=S]
#                          [--output=FILE]
#
# --install       first install the missing peer packages
#                 (scripts/setup.sh --peers; needs root or sudo).
# --runs=N        runs of every workload; the best counts (default 3).
# --min-time=S    Google Benchmark's minimum time per run (default 0.5).
# --output=FILE   also write the whole report (docs/performance.md).
#
# The build goes to build/peers (the release preset's flags, tests off), the
# raw figures to build/peers/performance/. A peer that is not installed is
# left out (its cells read "-"); a target missed prints "below target" but
# still exits 0 (this is a measuring tool). Exit 2 if the build failed, 1 if
# a benchmark failed.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 2

install=0
runs=3
min_time=0.5
output=""
for arg in "$@"; do
  case "$arg" in
    --install) install=1 ;;
    --runs=*) runs="${arg#--runs=}" ;;
    --min-time=*) min_time="${arg#--min-time=}" ;;
    --output=*) output="${arg#--output=}" ;;
    *)
      echo "usage: $0 [--install] [--runs=N] [--min-time=S] [--output=FILE]" >&2
      exit 2
      ;;
  esac
done

if [ "$install" = 1 ]; then bash scripts/setup.sh --peers || exit 2; fi

bin=build/peers
work=$bin/performance
started=$(date -u '+%Y-%m-%d %H:%M UTC')
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

# Configure and build.
if ! cmake --preset release -B "$bin" -DFREEFORM_PEER_BENCHMARKS=ON \
  -DFREEFORM_BUILD_TESTS=OFF >/dev/null; then
  echo "configure failed" >&2
  exit 2
fi
targets=(core_bench bspline_bench surface_bench construction_bench
  operations_bench)
available=$(cmake --build "$bin" --target help)
for peer in occt_workloads_bench eigen_workloads_bench; do
  if grep -q "^$peer:" <<<"$available"; then
    targets+=("$peer")
  else
    echo "$peer is not built (its library was not found)" >&2
  fi
done
if ! cmake --build "$bin" -j "$(nproc)" --target "${targets[@]}" >&2; then
  echo "build failed" >&2
  exit 2
fi
rm -rf "$work"
mkdir -p "$work"

failed=0
# bench PROGRAM FILTER: one Google Benchmark program, figures to
# $work/PROGRAM.json, its console output to the terminal.
bench() {
  echo "== $1" >&2
  if ! "$bin/bench/$1" --benchmark_filter="$2" \
    --benchmark_repetitions="$runs" --benchmark_min_time="$min_time" \
    --benchmark_out="$work/$1.json" --benchmark_out_format=json >&2; then
    failed=1
  fi
}

# peer NAME COMMAND...: runs a peer, its RESULT lines to $work/results.txt.
peer() {
  local name=$1
  shift
  echo "== $name" >&2
  if ! "$@" | tee -a "$work/results.txt" >&2; then
    echo "$name FAILED" >&2
    failed=1
  fi
}

bench core_bench 'BM_W4_CubicBezierPositions'
bench bspline_bench 'BM_W[127]_'
bench surface_bench 'BM_W[37]_BicubicSurfaceGrid'
bench construction_bench 'BM_W5_GlobalCubicInterpolation/100000$|BM_W6_'
python3 scripts/performance_report.py results "$work"/*_bench.json \
  >"$work/results.txt" || failed=1

[ -x "$bin/bench/occt_workloads_bench" ] &&
  peer OpenCASCADE "$bin/bench/occt_workloads_bench" "$runs"
[ -x "$bin/bench/eigen_workloads_bench" ] &&
  peer Eigen "$bin/bench/eigen_workloads_bench" "$runs"
# scipy: the first python3 that has it (Debian's, when another comes first).
scipy_python=""
for python in python3 /usr/bin/python3; do
  if "$python" -c 'import scipy' 2>/dev/null; then
    scipy_python=$python
    break
  fi
done
if [ -n "$scipy_python" ]; then
  peer scipy "$scipy_python" bench/peers/scipy_workloads.py "$runs"
else
  echo "scipy is not installed: no scipy figures" >&2
fi

# The operations without a peer, after the comparison.
echo "== operations_bench" >&2
"$bin/bench/operations_bench" --benchmark_repetitions="$runs" \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$work/operations.json" --benchmark_out_format=json >&2 ||
  failed=1

# header_version FILE PREFIX: the values of PREFIX{MAJOR,MINOR,...} as
# #defined in FILE, joined by dots ("-" when absent): a library's version.
header_version() {
  awk -v prefix="$2" '$1 == "#define" && $2 ~ "^" prefix && $3 ~ /^[0-9]+$/ {
      printf "%s%s", sep, $3; sep = "."
    }' "$1" 2>/dev/null | grep . || echo -
}
{
  echo "command: bash scripts/performance.sh $*"
  echo "date: $started"
  echo "commit: $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- \
    ':!docs/performance.md' || echo ' with uncommitted changes')"
  echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), \
$(nproc) cores"
  echo "load average (1, 5, 15 min) before: $load_before, after: \
$(cut -d' ' -f1-3 /proc/loadavg)"
  echo "compiler: $(c++ --version | head -1)"
  echo "OpenCASCADE: $(header_version \
    /usr/include/opencascade/Standard_Version.hxx \
    'OCC_VERSION_(MAJOR|MINOR|MAINTENANCE)$')"
  echo "Eigen: $(header_version /usr/include/eigen3/Eigen/src/Core/util/Macros.h \
    'EIGEN_(WORLD|MAJOR|MINOR)_VERSION$')"
  [ -n "$scipy_python" ] && echo "scipy: $("$scipy_python" -c \
    'import numpy, scipy; print(scipy.__version__, "(numpy", numpy.__version__ + ")")')"
  echo "runs: best of $runs, Google Benchmark minimum time $min_time s a run"
} >"$work/about.txt"

echo
python3 scripts/performance_report.py table "$work/results.txt" \
  "$work/operations.json" --about "$work/about.txt" \
  ${output:+--output "$output"} || failed=1
[ -n "$output" ] && echo "wrote $output" >&2
[ "$failed" = 0 ] || echo "some benchmarks FAILED: the figures are incomplete" >&2
exit "$failed"
