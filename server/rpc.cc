#include "rpc.h"

#include <chrono>

#include "errors.h"
#include "spdlog/spdlog.h"

namespace freeform::server {
namespace {

// The call's deadline on the steady clock (gRPC reports it on the system
// clock; an infinite deadline comes back as a far-future time point).
std::optional<CancellationToken::Clock::time_point> SteadyDeadline(
    const grpc::ServerContext& context) {
  const auto deadline = context.deadline();
  if (deadline == std::chrono::system_clock::time_point::max()) {
    return std::nullopt;
  }
  const auto remaining = deadline - std::chrono::system_clock::now();
  if (remaining > std::chrono::hours(24 * 365)) return std::nullopt;
  return CancellationToken::Clock::now() +
         std::chrono::duration_cast<CancellationToken::Clock::duration>(
             remaining);
}

}  // namespace

grpc::Status RunRpc(
    absl::string_view method, grpc::ServerContext* context,
    const google::protobuf::Message& request,
    const google::protobuf::Message* response,
    absl::FunctionRef<absl::Status(const CancellationToken&)> handler,
    const size_t* streamed_bytes) {
  const auto started = std::chrono::steady_clock::now();
  CancellationToken token;
  if (auto deadline = SteadyDeadline(*context); deadline.has_value()) {
    token.SetDeadline(*deadline);
  }
  token.SetPoll([context] { return context->IsCancelled(); });

  const absl::Status result = handler(token);
  grpc::Status status = ToGrpcStatus(result);

  const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::steady_clock::now() - started)
                          .count();
  const size_t response_bytes =
      response != nullptr && status.ok()
          ? response->ByteSizeLong()
          : (streamed_bytes != nullptr ? *streamed_bytes : 0);
  spdlog::info(
      "rpc method={} peer={} request_bytes={} response_bytes={} "
      "status={} micros={}{}{}",
      std::string(method), context->peer(), request.ByteSizeLong(),
      response_bytes, absl::StatusCodeToString(result.code()), micros,
      status.ok() ? "" : " error=\"",
      status.ok() ? "" : status.error_message() + "\"");
  return status;
}

}  // namespace freeform::server
