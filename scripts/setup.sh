#!/usr/bin/env bash
# Installs the Debian 12 packages freeform needs to build and test, and only
# those that are missing. Safe to run again; needs root (or sudo).
#   scripts/setup.sh [--peers]
# --peers  also the peer libraries that scripts/performance.sh measures
#          freeform against (OpenCASCADE, scipy, Eigen).
set -euo pipefail

peers=0
for arg in "$@"; do
  case "$arg" in
    --peers) peers=1 ;;
    *) echo "usage: $0 [--peers]" >&2; exit 2 ;;
  esac
done

packages=(
  cmake ninja-build g++ pkg-config
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libabsl-dev libhwy-dev libspdlog-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # freeformd's Prometheus metrics (--metrics_listen): prometheus-cpp core
  # and pull (its HTTP exposer, on civetweb).
  prometheus-cpp-dev
  # google/rpc/status.proto and error_details.proto (google.rpc.BadRequest).
  golang-github-gogo-googleapis-dev
  # grpc/health/v1/health.proto for the client's health check.
  grpc-proto
  # Certificates for the TLS tests.
  openssl
  # The fuzz preset: clang with libFuzzer, ASan and UBSan, linked by lld
  # (docs/fuzzing.md).
  clang-14 libfuzzer-14-dev lld-14
)
if [ "$peers" = 1 ]; then
  packages+=(
    libocct-modeling-data-dev libocct-modeling-algorithms-dev
    libocct-foundation-dev python3-scipy libeigen3-dev
  )
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
