// RunRpc: the frame every freeformd handler runs in.
//
// It builds the RPC's CancellationToken (the call's deadline plus the
// client's cancellation), runs the handler, turns its absl::Status into a
// grpc::Status with field-path details, and writes one access-log line:
// method, peer, request and response bytes, status and microseconds.
// Thread-safe.
#ifndef FREEFORM_SERVER_RPC_H_
#define FREEFORM_SERVER_RPC_H_

#include <google/protobuf/message.h>
#include <grpcpp/server_context.h>
#include <grpcpp/support/sync_stream.h>

#include <algorithm>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "freeform/core/cancellation.h"

namespace freeform::server {

// RunRpc runs `handler` for `method`. Field paths in the handler's errors
// must be full paths into the request. `response` may be null for streaming
// RPCs (the logged size is then `*streamed_bytes`, when given).
grpc::Status RunRpc(
    absl::string_view method, grpc::ServerContext* context,
    const google::protobuf::Message& request,
    const google::protobuf::Message* response,
    absl::FunctionRef<absl::Status(const CancellationToken&)> handler,
    const size_t* streamed_bytes = nullptr);

// StreamChunks writes the answer for items [0, total) as consecutive chunks
// of at most `chunk` items: `fill(first, last, response)` fills one message,
// which is then written. Stops early when the token or the client stops;
// adds the bytes written to `streamed_bytes`.
template <typename Response>
absl::Status StreamChunks(
    size_t total, size_t chunk, const CancellationToken& token,
    grpc::ServerWriter<Response>* writer, size_t& streamed_bytes,
    absl::FunctionRef<absl::Status(size_t, size_t, Response&)> fill) {
  Response response;
  for (size_t first = 0; first < total; first += chunk) {
    if (token.IsCancelled()) return token.status();
    response.Clear();
    const size_t last = std::min(total, first + chunk);
    if (absl::Status status = fill(first, last, response); !status.ok()) {
      return status;
    }
    streamed_bytes += response.ByteSizeLong();
    if (!writer->Write(response)) {
      return absl::CancelledError("the client stopped reading");
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_RPC_H_
