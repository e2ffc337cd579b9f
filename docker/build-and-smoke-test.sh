#!/usr/bin/env bash
# Builds the freeformd image with rootful podman and smoke-tests it:
#
#   1. installs podman, runc, debootstrap and haproxy if missing (apt);
#   2. writes a containers.conf that works on these machines (runc,
#      cgroupfs, file events logger, ulimits within the host's hard limits);
#   3. imports a debootstrap'd debian:bookworm base image if none is present
#      (no registry is reachable; apt's mirror is);
#   4. checks docker/haproxy.cfg with `haproxy -c` (compose hostnames
#      replaced by 127.0.0.1, since they only resolve inside compose);
#   5. builds docker/Dockerfile, runs the image with -p 127.0.0.1:PORT:50051,
#      waits for `freeform health` (through the published port) to say
#      SERVING, evaluates a cubic with `freeform eval`, runs the image's
#      HEALTHCHECK, checks the server runs as a non-root user;
#   6. stops it with SIGTERM (`podman stop`) and checks it exits with
#      status 0 within 2 s; removes the container.
#
# Usage (Debian 12, as root, from anywhere):
#   docker/build-and-smoke-test.sh                       # builds from source
#   docker/build-and-smoke-test.sh --prebuilt BUILD_DIR  # packages a build
# --prebuilt takes the binaries of a Debian 12 CMake build (e.g.
# build/release) instead of compiling the project again inside the image:
# they are installed into docker/prebuilt/ of a copy of the build context,
# and the Dockerfile's build stage then only copies them (docker/prebuilt/
# README.md). The runtime stage is the same either way. This is what the
# ctest label `container` runs.
#
# Environment:
#   FREEFORM_REPO        repository root (default: the parent of docker/)
#   FREEFORM_PODMAN_DIR  podman storage (default /var/tmp/freeform-podman)
#   IMAGE                image tag to build (default localhost/freeform:VERSION,
#                        VERSION from the CMake project)
#   PORT                 host port on 127.0.0.1 (default: a free one)
#   BUILD_TIMEOUT        seconds allowed for the image build (default 2400)
#   KEEP_IMAGE=1         keep the built image (default: removed at the end;
#                        the base image and the build cache layers are kept)
#   SKIP_BUILD=1         reuse an existing $IMAGE instead of building it
set -euo pipefail

PREBUILT_BUILD=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prebuilt) [ $# -ge 2 ] || { echo "--prebuilt needs BUILD_DIR" >&2; exit 2; }
                PREBUILT_BUILD="$(cd "$2" && pwd)"; shift 2 ;;
    *) echo "usage: $0 [--prebuilt BUILD_DIR]" >&2; exit 2 ;;
  esac
done

readonly REPO_ROOT="${FREEFORM_REPO:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
readonly STATE_DIR="${FREEFORM_PODMAN_DIR:-/var/tmp/freeform-podman}"
readonly VERSION="$(sed -n 's/^project(freeform VERSION \([0-9.]*\).*/\1/p' "$REPO_ROOT/CMakeLists.txt")"
readonly IMAGE="${IMAGE:-localhost/freeform:${VERSION}}"
readonly BASE_IMAGE="docker.io/library/debian:bookworm"
readonly BUILD_TIMEOUT="${BUILD_TIMEOUT:-2400}"
readonly CONTAINER="freeform-smoke-$$"
readonly START_TIMEOUT=60   # seconds for the server to report SERVING
readonly STOP_TIMEOUT=30    # podman stop -t (SIGKILL after that)
readonly STOP_BUDGET_MS=2000  # a prompt exit takes less than this

# Rootful podman with its storage under STATE_DIR (flags, not
# CONTAINERS_STORAGE_CONF, which makes every call hang about 20 s).
pm() { podman --root "$STATE_DIR/root" --runroot "$STATE_DIR/runroot" "$@"; }

log() { printf '[smoke %(%H:%M:%S)T] %s\n' -1 "$*" >&2; }
die() { log "FAIL: $*"; exit 1; }

[ "$(id -u)" -eq 0 ] || die "run as root (rootful podman)"
grep -q '^VERSION_CODENAME=bookworm' /etc/os-release 2>/dev/null \
  || log "warning: not Debian 12 (bookworm); continuing anyway"

WORK_DIR="$(mktemp -d /var/tmp/freeform-smoke.XXXXXX)"
ROOTFS=""
cleanup() {
  local status=$?
  set +e
  if [ -n "${CONTAINERS_CONF:-}" ] && command -v podman >/dev/null; then
    pm rm -f -t 0 "$CONTAINER" >/dev/null 2>&1
    if [ "${KEEP_IMAGE:-0}" != 1 ] && [ "${SKIP_BUILD:-0}" != 1 ]; then
      pm rmi -f "$IMAGE" >/dev/null 2>&1
    fi
  fi
  [ -n "$ROOTFS" ] && rm -rf "$ROOTFS"
  rm -rf "$WORK_DIR"
  if [ "$status" -eq 0 ]; then log "PASS"; else log "exit status $status"; fi
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# --- 1. packages ----------------------------------------------------------
need=()
for package in podman runc debootstrap haproxy; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
    || need+=("$package")
done
if [ ${#need[@]} -gt 0 ]; then
  log "installing ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  timeout 600 apt-get update -q
  timeout 900 apt-get install -y -q --no-install-recommends "${need[@]}"
fi

# --- 2. containers.conf ---------------------------------------------------
nofile="$(ulimit -Hn)"
[ "$nofile" = unlimited ] && nofile=1048576
nproc=32768
hard_nproc="$(ulimit -Hu)"
if [ "$hard_nproc" != unlimited ] && [ "$hard_nproc" -lt "$nproc" ]; then nproc="$hard_nproc"; fi
cat >"$WORK_DIR/containers.conf" <<EOF
[containers]
default_ulimits = ["nofile=${nofile}:${nofile}", "nproc=${nproc}:${nproc}"]

[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
events_logger = "file"
EOF
export CONTAINERS_CONF="$WORK_DIR/containers.conf"
unset CONTAINERS_STORAGE_CONF
mkdir -p "$STATE_DIR/root" "$STATE_DIR/runroot"

# --- 3. base image ----------------------------------------------------------
# The first URIs: line (deb822) or deb line (one-line format) of the host's
# apt sources is the Debian mirror.
apt_mirror() {
  local file uri
  for file in /etc/apt/sources.list.d/debian.sources /etc/apt/sources.list.d/*.sources; do
    [ -f "$file" ] || continue
    uri="$(awk '/^URIs:/ { for (i = 2; i <= NF; i++) if ($i !~ /security/) { print $i; exit } }' "$file")"
    [ -n "$uri" ] && { echo "$uri"; return; }
  done
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$file" ] || continue
    uri="$(awk '$1 == "deb" { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z]+:\/\//) { if ($i !~ /security/) { print $i; exit } else break } }' "$file")"
    [ -n "$uri" ] && { echo "$uri"; return; }
  done
  echo "http://deb.debian.org/debian"
}

if pm image exists "$BASE_IMAGE"; then
  log "base image $BASE_IMAGE present"
else
  mirror="$(apt_mirror)"
  log "debootstrap bookworm from $mirror (about a minute)"
  ROOTFS="$(mktemp -d /var/tmp/freeform-rootfs.XXXXXX)"
  timeout 900 debootstrap --variant=minbase bookworm "$ROOTFS" "$mirror" >"$WORK_DIR/debootstrap.log" 2>&1 \
    || { tail -n 30 "$WORK_DIR/debootstrap.log" >&2; die "debootstrap failed"; }
  # The image uses the host's apt sources (same mirror, security suite too).
  rm -f "$ROOTFS/etc/apt/sources.list"
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    if [ -f "$file" ]; then cp "$file" "$ROOTFS${file}"; fi
  done
  # The mirror may be a dated snapshot whose Release files have expired.
  echo 'Acquire::Check-Valid-Until "false";' >"$ROOTFS/etc/apt/apt.conf.d/99freeform-snapshot"
  rm -rf "$ROOTFS"/var/lib/apt/lists/* "$ROOTFS"/var/cache/apt/archives/*.deb
  tar --numeric-owner -C "$ROOTFS" -c . \
    | pm import --quiet \
        --change 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' \
        --change 'CMD ["bash"]' \
        - "$BASE_IMAGE" >/dev/null
  rm -rf "$ROOTFS"; ROOTFS=""
  log "imported $BASE_IMAGE"
fi

# --- 4. haproxy.cfg ---------------------------------------------------------
sed -E 's/freeformd-[0-9]+:50051/127.0.0.1:50051/g' "$REPO_ROOT/docker/haproxy.cfg" >"$WORK_DIR/haproxy.cfg"
haproxy -c -f "$WORK_DIR/haproxy.cfg" >"$WORK_DIR/haproxy-check.log" 2>&1 \
  || { cat "$WORK_DIR/haproxy-check.log" >&2; die "haproxy -c rejects docker/haproxy.cfg"; }
log "haproxy -c: docker/haproxy.cfg is valid"

# --- 5. build and run -------------------------------------------------------
if [ "${SKIP_BUILD:-0}" = 1 ]; then
  pm image exists "$IMAGE" || die "SKIP_BUILD=1 but $IMAGE does not exist"
  log "reusing $IMAGE"
else
  context="$REPO_ROOT"
  if [ -n "$PREBUILT_BUILD" ]; then
    # A context of its own: the folders the Dockerfile copies, with the
    # build's install tree in docker/prebuilt.
    context="$WORK_DIR/context"
    mkdir -p "$context"
    for entry in CMakeLists.txt CMakePresets.json scripts proto core io server client cmake docker examples; do
      cp -a "$REPO_ROOT/$entry" "$context/"
    done
    # The playground's sources, without web/node_modules.
    mkdir -p "$context/web"
    for entry in package.json package-lock.json CMakeLists.txt playground; do
      cp -a "$REPO_ROOT/web/$entry" "$context/web/"
    done
    cmake --install "$PREBUILT_BUILD" --prefix "$context/docker/prebuilt" --strip >"$WORK_DIR/install.log" 2>&1 \
      || { cat "$WORK_DIR/install.log" >&2; die "cmake --install $PREBUILT_BUILD failed"; }
    log "packaging the binaries of $PREBUILT_BUILD"
  fi
  log "building $IMAGE (cold: minutes; log in $WORK_DIR/build.log)"
  start=$SECONDS
  if ! timeout "$BUILD_TIMEOUT" podman --root "$STATE_DIR/root" --runroot "$STATE_DIR/runroot" \
      build --pull=never --format docker -f "$context/docker/Dockerfile" -t "$IMAGE" \
      "$context" >"$WORK_DIR/build.log" 2>&1; then
    tail -n 60 "$WORK_DIR/build.log" >&2
    die "image build failed"
  fi
  pm image exists "$IMAGE" || die "the build left no image $IMAGE"
  log "built $IMAGE in $((SECONDS - start)) s ($(pm image inspect --format '{{.Size}}' "$IMAGE") bytes)"
fi

if [ -z "${PORT:-}" ]; then
  PORT="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])' 2>/dev/null \
          || echo $((20000 + RANDOM % 20000)))"
fi
# No systemd here to run the HEALTHCHECK on a timer: it is run by hand below.
# (podman still logs that it cannot reach systemd: kept out of the way.)
pm run -d --name "$CONTAINER" --health-interval=disable -p "127.0.0.1:${PORT}:50051" "$IMAGE" \
  >/dev/null 2>"$WORK_DIR/run.err" || { cat "$WORK_DIR/run.err" >&2; die "podman run failed"; }
log "started $CONTAINER on 127.0.0.1:$PORT"

# The CLI talks to the published port: the host build's if there is one,
# else the image's own, in a throwaway container on the host's network.
host_cli="${PREBUILT_BUILD:-$REPO_ROOT/build/release}/client/freeform"
cli() {
  if [ -x "$host_cli" ]; then
    timeout 10 "$host_cli" "$@" --address "127.0.0.1:$PORT"
  else
    timeout 20 podman --root "$STATE_DIR/root" --runroot "$STATE_DIR/runroot" \
      run --rm -i --network=host --no-healthcheck --entrypoint /opt/freeform/bin/freeform "$IMAGE" \
      "$@" --address "127.0.0.1:$PORT"
  fi
}
if [ -x "$host_cli" ]; then log "client: host CLI $host_cli"; else log "client: the image's CLI (--network=host)"; fi

deadline=$((SECONDS + START_TIMEOUT))
until out="$(cli health </dev/null 2>&1)" && grep -q SERVING <<<"$out" && ! grep -q NOT_SERVING <<<"$out"; do
  if [ "$(pm inspect --format '{{.State.Running}}' "$CONTAINER")" != true ]; then
    pm logs "$CONTAINER" >&2 || true
    die "container exited before serving"
  fi
  [ "$SECONDS" -lt "$deadline" ] || { pm logs "$CONTAINER" >&2 || true; die "not SERVING after ${START_TIMEOUT} s: $out"; }
  sleep 1
done
log "health: $out"

# The worked cubic of the integration tests: B(0.5) = (2, 1.5).
request='{"curve": {"bezier": {"control_points": {"dimension": 2, "coordinates": [0, 0, 1, 2, 3, 2, 4, 0]}}},
          "parameters": {"list": {"values": [0, 0.5, 1]}}, "derivative_order": 1}'
out="$(cli eval --file - <<<"$request" 2>&1)" || die "freeform eval failed: $out"
out="$(tr -d ' \t\n' <<<"$out")"
grep -q '"coordinates":\[0,0,2,1.5,4,0\]' <<<"$out" || die "unexpected eval answer: $out"
log "eval: $out"

grep -q "freeformd listening on 0.0.0.0:50051" <<<"$(pm logs "$CONTAINER" 2>&1)" \
  || { pm logs "$CONTAINER" >&2; die "no 'freeformd listening on 0.0.0.0:50051' line in the logs"; }

uid="$(pm exec "$CONTAINER" id -u)"
[ "$uid" != 0 ] || die "the server runs as root"
log "server runs as uid $uid"

if [ "$(pm image inspect --format '{{if .Config.Healthcheck}}yes{{end}}' "$IMAGE" 2>/dev/null)" = yes ]; then
  timeout 20 podman --root "$STATE_DIR/root" --runroot "$STATE_DIR/runroot" healthcheck run "$CONTAINER" \
    || die "the image's HEALTHCHECK reports unhealthy"
  log "image HEALTHCHECK: healthy"
else
  die "image has no HEALTHCHECK (built without --format docker?)"
fi

# --- 6. SIGTERM -------------------------------------------------------------
log "podman stop (SIGTERM, kill after ${STOP_TIMEOUT} s)"
start_ns=$(date +%s%N)
timeout $((STOP_TIMEOUT + 30)) podman --root "$STATE_DIR/root" --runroot "$STATE_DIR/runroot" \
  stop -t "$STOP_TIMEOUT" "$CONTAINER" >/dev/null 2>"$WORK_DIR/stop.err" \
  || { cat "$WORK_DIR/stop.err" >&2; die "podman stop failed"; }
elapsed_ms=$(( ($(date +%s%N) - start_ns) / 1000000 ))
code="$(pm inspect --format '{{.State.ExitCode}}' "$CONTAINER")"
log "stopped in ${elapsed_ms} ms, exit status $code"
[ "$code" = 0 ] || { pm logs "$CONTAINER" 2>&1 | tail -n 20 >&2; die "exit status $code after SIGTERM (expected 0)"; }
[ "$elapsed_ms" -lt "$STOP_BUDGET_MS" ] || die "took ${elapsed_ms} ms to stop (budget ${STOP_BUDGET_MS} ms)"
