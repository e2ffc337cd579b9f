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

// RunUnimplemented answers UNIMPLEMENTED for `method`, saying which issue
// brings it, and logs the call like RunRpc.
grpc::Status RunUnimplemented(absl::string_view method,
                              grpc::ServerContext* context,
                              const google::protobuf::Message& request,
                              absl::string_view issue);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_RPC_H_
