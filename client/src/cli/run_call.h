// RunCall: the shape of most freeform CLI subcommands. It reads a request
// as proto3 JSON, lets the subcommand's flags amend it, sends one unary
// RPC and hands the answer to an output; RunJsonCall prints the answer as
// JSON.
#ifndef FREEFORM_CLIENT_CLI_RUN_CALL_H_
#define FREEFORM_CLIENT_CLI_RUN_CALL_H_

#include <memory>
#include <string>
#include <type_traits>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "common.h"
#include "freeform/client.h"
#include "input.h"
#include "output.h"

namespace freeform::cli {

// A unary RPC of a generated stub, e.g. &v1::CurveService::Stub::ArcLength.
template <typename Stub, typename Request, typename Response>
using RpcMethod = grpc::Status (Stub::*)(grpc::ClientContext*, const Request&,
                                         Response*);

// Changes a request read from JSON before it is sent (from flags); an
// error is the user's (kExitUsage).
template <typename Request>
using Amend = std::type_identity_t<absl::FunctionRef<absl::Status(Request&)>>;

// Prints an answer and returns the exit status; the client is there for
// follow-up calls.
template <typename Request, typename Response>
using Output = std::type_identity_t<
    absl::FunctionRef<int(Client&, const Request&, const Response&)>>;

// An Amend that sends the request as read.
template <typename Request>
absl::Status KeepRequest(Request&) {
  return absl::OkStatus();
}

// RunCall reads the request from `file` as proto3 JSON, lets `amend` change
// it, calls `method` and hands the answer to `output`. Returns the exit
// status.
template <typename Stub, typename Request, typename Response>
int RunCall(const CommonFlags& flags, const std::string& file,
            RpcMethod<Stub, Request, Response> method, Amend<Request> amend,
            Output<Request, Response> output) {
  absl::StatusOr<Request> request = ParseJson<Request>(file);
  if (!request.ok()) return InputError(request.status());
  if (absl::Status amended = amend(*request); !amended.ok()) {
    return InputError(amended);
  }
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  absl::StatusOr<Response> response = client->Unary(method, *request);
  if (!response.ok()) return ReportError(response.status());
  return output(*client, *request, *response);
}

// RunJsonCall is RunCall that sends the request as read and prints the
// answer as JSON.
template <typename Stub, typename Request, typename Response>
int RunJsonCall(const CommonFlags& flags, const std::string& file,
                RpcMethod<Stub, Request, Response> method) {
  return RunCall(flags, file, method, &KeepRequest<Request>,
                 [&](Client&, const Request&, const Response& response) {
                   return PrintJson(flags, response);
                 });
}

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_RUN_CALL_H_
