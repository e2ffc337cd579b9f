#!/usr/bin/env bash
# Installs the Debian 12 packages freeform needs to build and test, and only
# those that are missing, then the npm packages of web/package-lock.json
# (scripts/web_packages.sh: the playground page's build tools and three.js,
# and the browser test's playwright-core). Safe to run again; needs root (or
# sudo).
#   scripts/setup.sh [--peers | --build-only]
# --peers       also the peer libraries that scripts/performance.sh measures
#               freeform against (OpenCASCADE, scipy, Eigen).
# --build-only  only what building freeformd, the CLI and the client library
#               needs, without tests and benchmarks (the container image's
#               build stage).
set -euo pipefail

peers=0 build_only=0
for arg in "$@"; do
  case "$arg" in
    --peers) peers=1 ;;
    --build-only) build_only=1 ;;
    *) echo "usage: $0 [--peers | --build-only]" >&2; exit 2 ;;
  esac
done

packages=(
  cmake ninja-build g++ pkg-config
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libabsl-dev libhwy-dev libspdlog-dev libcli11-dev nlohmann-json3-dev
  # freeformd's Prometheus metrics (--metrics_listen): prometheus-cpp core
  # and pull (its HTTP exposer), on civetweb, whose options and request
  # hook freeformd sets.
  prometheus-cpp-dev libcivetweb-dev
  # freeformd checks its TLS key against its certificate with libcrypto.
  libssl-dev
  # grpc/health/v1/health.proto for the client's health check.
  grpc-proto
)
# The playground page that freeformd embeds is bundled at build time by
# esbuild from npm (web/CMakeLists.txt): node and npm. Any node >= 18
# serves, so one that is already there (e.g. from NodeSource, whose nodejs
# bundles npm) is kept. The Node client example and its test
# (examples/node) use them too.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev
  # The Python client example and its test (examples/python, docs/clients.md):
  # stubs come from protoc's grpc_python_plugin (protobuf-compiler-grpc).
  python3-grpcio python3-protobuf
  # The Python package (clients/python) and its test: numpy arrays, built
  # by python3-build with setuptools and wheel, installed into a venv, its
  # type hints checked by mypy.
  python3-numpy python3-build python3-setuptools python3-wheel python3-venv
  mypy
  # Certificates for the TLS tests.
  openssl
  # The HTTP gateway's test and benchmark talk HTTP with libcurl; the
  # README's HTTP example runs curl.
  libcurl4-openssl-dev curl
  # The scale-out test (tests/integration/scale_out_test.cc) serves its
  # replicas' name with dnsmasq on a loopback port. dnsmasq-base is the
  # binary alone: unlike the dnsmasq package it installs no service, so
  # nothing takes port 53 or changes the machine's resolver.
  dnsmasq-base
  # The fuzz preset: clang with libFuzzer, ASan and UBSan, linked by lld
  # (docs/fuzzing.md).
  clang-14 libfuzzer-14-dev lld-14
  # The playground's browser test (tests/browser/): headless chromium,
  # driven by playwright-core from npm.
  chromium
)
if [ "$build_only" = 0 ]; then
  packages+=("${test_packages[@]}")
fi
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
else
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The npm packages, where web/ is there (the container's build stage runs
# this script before it copies the sources, and scripts/web_packages.sh
# after).
web_dir="$(dirname "$0")/../web"
if [ -f "$web_dir/package-lock.json" ]; then
  if [ "$build_only" = 1 ]; then
    bash "$(dirname "$0")/web_packages.sh" --omit-dev
  else
    bash "$(dirname "$0")/web_packages.sh"
  fi
fi
