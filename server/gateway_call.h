// GatewayCall: how the HTTP gateway (http_gateway.h) calls freeformd's own
// services: in-process, through grpc::GenericStub on the server's
// InProcessChannel, so every HTTP call runs in the same RpcFrame (rpc.h) as
// a gRPC call (admission, limits, deadline, metrics, access log) and the
// handlers have no second entry.
//
// ResolveMethod maps a URL path to a method of freeform.v1's services (and
// nothing else: not health, not reflection). InProcessCaller makes the call
// with the HTTP request's deadline and marks it as HTTP, with the client's
// address, for the metrics and the access log (transport.h). Thread-safe.
#ifndef FREEFORM_SERVER_GATEWAY_CALL_H_
#define FREEFORM_SERVER_GATEWAY_CALL_H_

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <grpcpp/channel.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/support/status.h>

#include <memory>
#include <optional>
#include <string>

#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"

namespace freeform::server {

// A freeform.v1 method the gateway serves.
struct GatewayMethod {
  // "/freeform.v1.CurveService/Evaluate": the URL path and gRPC's method.
  std::string path;
  // "CurveService.Evaluate": the access log's and the metrics' name.
  std::string name;
  const google::protobuf::Message* request_prototype = nullptr;
  const google::protobuf::Message* response_prototype = nullptr;
  bool server_streaming = false;
};

// ResolveMethod returns the method at `path`; NOT_FOUND when the path
// names no unary or server-streaming method of freeform.v1's CurveService
// or SurfaceService.
absl::StatusOr<GatewayMethod> ResolveMethod(absl::string_view path);

// What the gateway passes on with a call.
struct CallSettings {
  // From Connect-Timeout-Ms; none leaves the server's --max_call_time.
  std::optional<absl::Duration> timeout;
  // The HTTP client, as the access log names it ("ipv4:127.0.0.1:40000").
  std::string client;
};

class InProcessCaller {
 public:
  explicit InProcessCaller(std::shared_ptr<grpc::Channel> channel);

  // Unary calls `method` with the serialized `request` and returns its
  // status; an OK call leaves the serialized answer in `response`.
  grpc::Status Unary(const GatewayMethod& method, const CallSettings& settings,
                     const std::string& request, std::string& response);

  // Stream calls the server-streaming `method` and hands each serialized
  // message to `on_message`, which returns false to stop (the call is then
  // cancelled); returns the call's final status.
  grpc::Status Stream(const GatewayMethod& method, const CallSettings& settings,
                      const std::string& request,
                      absl::FunctionRef<bool(std::string)> on_message);

 private:
  grpc::GenericStub stub_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_GATEWAY_CALL_H_
