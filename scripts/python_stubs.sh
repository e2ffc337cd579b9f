#!/usr/bin/env bash
# Generates the Python messages and gRPC stubs of freeform.v1 and of the
# google.rpc error model (google.rpc.Status, google.rpc.BadRequest) into
# OUT_DIR, with Debian's protoc and grpc_python_plugin
# (protobuf-compiler-grpc). The stubs are build output: put OUT_DIR on
# PYTHONPATH and use Debian's python3 (python3-grpcio, python3-protobuf).
#   scripts/python_stubs.sh OUT_DIR
# e.g. scripts/python_stubs.sh build/python (docs/clients.md).
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 OUT_DIR" >&2
  exit 2
fi
out_dir=$1
proto_dir="$(cd "$(dirname "$0")/../proto" && pwd)"
plugin=$(command -v grpc_python_plugin) || {
  echo "$0: grpc_python_plugin not found: run scripts/setup.sh" >&2
  exit 1
}

mkdir -p "$out_dir"
# The include roots are proto/ and proto/third_party/; the names protoc
# sees (freeform/v1/..., google/rpc/...) become the Python modules
# freeform.v1.*_pb2 and google.rpc.*_pb2 (namespace packages).
protoc --proto_path="$proto_dir" --proto_path="$proto_dir/third_party" \
  --python_out="$out_dir" --grpc_python_out="$out_dir" \
  --plugin=protoc-gen-grpc_python="$plugin" \
  "$proto_dir"/freeform/v1/*.proto
protoc --proto_path="$proto_dir/third_party" --python_out="$out_dir" \
  "$proto_dir"/third_party/google/rpc/status.proto \
  "$proto_dir"/third_party/google/rpc/error_details.proto
